// Self-pair table files (fastron::parseSelfPairTables): what is accepted holds together.
#include <cmath>

#include "fastron/geometry/self_pair_table_file.h"
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  fuzz::readOrRefuse("fuzz.self-pairs", [&] {
    const SelfPairTableFile file = parseSelfPairTables(fuzz::textOf(data, size), "fuzz.self-pairs");
    for (const SelfPairTable& t : file.tables) {
      if (t.axes < 1 || t.axes > 2) fuzz::finding("a table of other than 1 or 2 axes", "");
      if (t.distance.size() != t.nodes[0] * t.nodes[1])
        fuzz::finding("a table whose distances are not one per node", "");
      for (const float d : t.distance)
        if (!std::isfinite(d)) fuzz::finding("a non-finite distance was accepted", "");
      const double q[2] = {0.5, -0.25};
      if (t.coordinate[0] < 2 && (t.axes < 2 || t.coordinate[1] < 2)) (void)t.lowerBound(q);
    }
  });
  return 0;
}
