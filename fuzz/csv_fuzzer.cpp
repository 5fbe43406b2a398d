// CSV datasets (fastron::parseCsv).
#include <cmath>

#include "fastron/core/dataset.h"
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  fuzz::readOrRefuse("fuzz.csv", [&] {
    const Dataset d = parseCsv(fuzz::textOf(data, size), "fuzz.csv");
    if (d.size() == 0 || d.dim() == 0 || static_cast<std::size_t>(d.points.rows()) != d.size())
      fuzz::finding("a dataset without rows or columns was accepted", "");
    if (!d.points.allFinite()) fuzz::finding("a non-finite value was accepted", "");
    for (const auto label : d.labels)
      if (label != 1 && label != -1) fuzz::finding("a label other than +1 / -1 was accepted", "");
    if (!d.columnNames.empty() && d.columnNames.size() != d.dim())
      fuzz::finding("a header of the wrong width was accepted", "");
  });
  return 0;
}
