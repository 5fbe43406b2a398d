// Path files (fastron::parsePathCsv) of a robot with joints a, b and c.
#include <cmath>

#include "fastron/planning/motion.h"
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  fuzz::readOrRefuse("fuzz.csv", [&] {
    const JointPath path = parsePathCsv(fuzz::textOf(data, size), "fuzz.csv", {"a", "b", "c"});
    if (path.empty()) fuzz::finding("a path without waypoints was accepted", "");
    for (const Eigen::VectorXd& q : path) {
      if (q.size() != 3) fuzz::finding("a waypoint of the wrong length was accepted", "");
      if (!q.allFinite()) fuzz::finding("a non-finite value was accepted", "");
    }
  });
  return 0;
}
