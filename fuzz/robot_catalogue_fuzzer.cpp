// The robot catalogue (fastron::parseRobotCatalogue, the format of data/robots/robots.yaml).
#include "fastron/geometry/robot_library.h"
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  fuzz::readOrRefuse("robots.yaml", [&] {
    parseRobotCatalogue(fuzz::textOf(data, size), "robots.yaml", "/nonexistent");
  });
  return 0;
}
