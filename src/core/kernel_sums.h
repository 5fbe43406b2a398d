#pragma once
// The model's float kernel sums, f(x) = sum_i w_i k(s_i, x), compiled once per SimdPath
// (kernel_sums_portable.cpp, kernel_sums_avx2.cpp, kernel_sums_avx512.cpp, each with its own
// instruction set) and reached through the table of the path in use. Private to core.

#include <cstddef>

#include "fastron/core/kernel.h"
#include "internal/simd_dispatch.h"

namespace fastron::detail {

/// Support points as the queries read them: `dim` blocks of `padded` floats (feature j of every
/// point, padded to a multiple of kSupportLanes with zero-weight points), then the weights.
struct SupportView {
  const float* soa = nullptr;
  const float* weights = nullptr;
  std::size_t padded = 0;
  std::size_t dim = 0;
  float gamma = 1;
  KernelType type = KernelType::RationalQuadratic;
  /// Point terms (Kernel::block): features per term, 0 for the one-term kernel; the weights of
  /// the whole term and of the point terms' sum (Kernel::wholeWeight, pointWeight).
  std::size_t block = 0;
  float wholeWeight = 1, pointWeight = 0;
};

/// Support points summed per step: one AVX-512 register, two AVX2 or four SSE2 registers.
inline constexpr std::size_t kSupportLanes = 16;
/// The most features a gradient sum keeps accumulators for (kMaxFeatureDimension, feature_map.h).
inline constexpr std::size_t kMaxFeatures = 192;
/// Queries scored per pass over the support set by `four`.
inline constexpr std::size_t kQueriesPerPass = 4;

struct KernelSums {
  /// f of one feature vector x (dim floats).
  float (*one)(const SupportView& support, const float* x);
  /// f of four consecutive feature vectors of xs (4 * dim floats), written to out[0..3]; each
  /// score equals `one` of the same vector, bit for bit.
  void (*four)(const SupportView& support, const float* xs, float* out);
  /// f of one feature vector x and its gradient with respect to x, written to dfdx (dim floats).
  float (*gradient)(const SupportView& support, const float* x, float* dfdx);
};

// One namespace per compiled path, defined by kernel_sums_impl.h.
namespace portable {
extern const KernelSums kKernelSums;
}
namespace avx2 {
extern const KernelSums kKernelSums;
}
namespace avx512 {
extern const KernelSums kKernelSums;
}

/// The table of the path in use: an atomic load per query.
inline const KernelSums& activeKernelSums() {
  return ofSimdPath(currentSimdPath(), portable::kKernelSums, avx2::kKernelSums,
                    avx512::kKernelSums);
}

}  // namespace fastron::detail
