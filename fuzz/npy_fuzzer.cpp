// NumPy .npy datasets (fastron::parseNpy).
#include "dataset_invariants.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fastron;
  fuzz::readOrRefuse("fuzz.npy",
                     [&] { fuzz::checkDataset(parseNpy(fuzz::textOf(data, size), "fuzz.npy")); });
  return 0;
}
