#include "fastron/core/motion_states.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "fastron/core/error.h"

namespace fastron {

std::size_t segmentCount(const double* a, const double* b, std::size_t dim, double resolution) {
  if (!(resolution > 0) || !std::isfinite(resolution)) {
    throw InvalidArgument("motion resolution must be positive, got " + std::to_string(resolution));
  }
  double squared = 0;
  for (std::size_t j = 0; j < dim; ++j) squared += (b[j] - a[j]) * (b[j] - a[j]);
  const double segments = std::ceil(std::sqrt(squared) / resolution);
  return segments < 1 ? 1 : static_cast<std::size_t>(segments);
}

void motionState(const double* a, const double* b, std::size_t dim, std::size_t i, std::size_t n,
                 double* out) {
  if (i == n) {
    std::copy_n(b, dim, out);
    return;
  }
  const double t = static_cast<double>(i) / static_cast<double>(n);
  for (std::size_t j = 0; j < dim; ++j) out[j] = a[j] + t * (b[j] - a[j]);
}

std::size_t bisectionIndex(std::size_t n, std::size_t row) {
  if (row == 0) return n;
  --row;
  std::size_t step = 1;
  while (step * 2 < n) step *= 2;
  for (; step >= 1; step /= 2) {
    const std::size_t count = (n + step - 1) / (2 * step);  // odd multiples of step below n
    if (row < count) return step * (2 * row + 1);
    row -= count;
  }
  return n;  // row >= n: no such row
}

// The loops of bisectionIndex, without its per-row search: planners call this for every motion.
void motionStates(const double* a, const double* b, std::size_t dim, std::size_t n,
                  std::vector<double>& out) {
  out.resize(n * dim);
  double* row = out.data();
  motionState(a, b, dim, n, n, row);
  std::size_t step = 1;
  while (step * 2 < n) step *= 2;
  for (; step >= 1; step /= 2) {
    for (std::size_t i = step; i < n; i += 2 * step) motionState(a, b, dim, i, n, row += dim);
  }
}

}  // namespace fastron
