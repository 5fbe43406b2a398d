#pragma once
// Vocabulary types shared by every layer.

#include <Eigen/Core>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// Robot configurations, one per row (row-major, so a row is a contiguous `const double*`).
using Configurations = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Collision labels, one per configuration: +1 in collision, -1 free (paper, Sec. II-A).
using Labels = std::vector<std::int8_t>;

/// The random engine behind every random choice; always constructed from an explicit seed.
using Rng = std::mt19937_64;

/// Largest configuration-space dimension a model accepts (queries keep the scaled query on the
/// stack, so the hot path never allocates).
inline constexpr std::size_t kMaxDimension = 64;

/// A duration in seconds.
inline double inSeconds(std::chrono::nanoseconds d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace fastron
