// SRDF disabled collisions and groups (fastron::parseSrdf), against the Panda.
#include "fastron/geometry/srdf.h"
#include "fuzz_reader.h"
#include "robot_for_fuzzing.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  const Robot& robot = fuzz::panda();
  fuzz::readOrRefuse("fuzz.srdf", [&] { parseSrdf(fuzz::textOf(data, size), "fuzz.srdf", robot); });
  return 0;
}
