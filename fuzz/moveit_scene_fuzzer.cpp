// MoveIt PlanningScene YAML (fastron::parseMoveItScene).
#include "fastron/geometry/scene_file.h"
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  fuzz::readOrRefuse("fuzz.yaml", [&] { parseMoveItScene(fuzz::textOf(data, size), "fuzz.yaml"); });
  return 0;
}
