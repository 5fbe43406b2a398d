// NumPy .npy datasets (fastron::parseNpy).
#include "fastron/core/dataset.h"
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  fuzz::readOrRefuse("fuzz.npy", [&] {
    const Dataset d = parseNpy(fuzz::textOf(data, size), "fuzz.npy");
    if (d.size() == 0 || d.dim() == 0 || static_cast<std::size_t>(d.points.rows()) != d.size())
      fuzz::finding("a dataset without rows or columns was accepted", "");
    if (!d.points.allFinite()) fuzz::finding("a non-finite value was accepted", "");
    for (const auto label : d.labels)
      if (label != 1 && label != -1) fuzz::finding("a label other than +1 / -1 was accepted", "");
  });
  return 0;
}
