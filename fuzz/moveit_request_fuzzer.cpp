// MoveIt MotionPlanRequest YAML (fastron::parseMoveItRequest), then its start and goal taken
// for the Panda as `fastron plan` takes them.
#include "fastron/geometry/moveit_request.h"
#include "fuzz_reader.h"
#include "robot_for_fuzzing.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  const Robot& robot = fuzz::panda();
  fuzz::readOrRefuse("fuzz.yaml", [&] {
    const PlanRequest request = parseMoveItRequest(fuzz::textOf(data, size), "fuzz.yaml");
    actuatedConfiguration(robot, request.start, "fuzz.yaml start");
    actuatedConfiguration(robot, request.goal, "fuzz.yaml goal");
  });
  return 0;
}
