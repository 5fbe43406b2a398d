#pragma once
// What a dataset that a reader accepted must be, whatever the bytes it came from.

#include "fastron/core/dataset.h"
#include "fuzz_reader.h"

namespace fastron::fuzz {

inline void checkDataset(const Dataset& d) {
  if (d.size() == 0 || d.dim() == 0 || static_cast<std::size_t>(d.points.rows()) != d.size())
    finding("a dataset without rows or columns was accepted", "");
  if (!d.points.allFinite()) finding("a non-finite value was accepted", "");
  for (const auto label : d.labels)
    if (label != 1 && label != -1) finding("a label other than +1 / -1 was accepted", "");
  if (!d.columnNames.empty() && d.columnNames.size() != d.dim())
    finding("a header of the wrong width was accepted", "");
}

}  // namespace fastron::fuzz
