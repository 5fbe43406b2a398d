// CSV datasets (fastron::parseCsv).
#include "dataset_invariants.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  fuzz::readOrRefuse("fuzz.csv",
                     [&] { fuzz::checkDataset(parseCsv(fuzz::textOf(data, size), "fuzz.csv")); });
  return 0;
}
