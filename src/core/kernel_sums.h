#pragma once
// The model's float kernel sums, f(x) = sum_i w_i k(s_i, x), compiled once per SimdPath
// (kernel_sums_portable.cpp, kernel_sums_avx2.cpp, kernel_sums_avx512.cpp, each with its own
// instruction set) and reached through the active path's table (simd.cpp). Private to core.

#include <atomic>
#include <cstddef>

#include "fastron/core/kernel.h"
#include "fastron/core/simd.h"

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
};

/// Support points summed per step: one AVX-512 register, two AVX2 or four SSE2 registers.
inline constexpr std::size_t kSupportLanes = 16;
/// Queries scored per pass over the support set by `four`.
inline constexpr std::size_t kQueriesPerPass = 4;

struct KernelSums {
  /// f of one feature vector x (dim floats).
  float (*one)(const SupportView& support, const float* x);
  /// f of four consecutive feature vectors of xs (4 * dim floats), written to out[0..3]; each
  /// score equals `one` of the same vector, bit for bit.
  void (*four)(const SupportView& support, const float* xs, float* out);
};

/// The table of one path (throws InvalidArgument when this build does not have it).
const KernelSums& kernelSumsOf(SimdPath path);
/// The active path's table; null until the first query or useSimdPath chooses one.
extern std::atomic<const KernelSums*> activeKernelSumsTable;
/// Chooses the table on first use (FASTRON_SIMD, else the widest path) and returns it.
const KernelSums& firstKernelSums();

/// The table of activeSimdPath(): inline, an atomic load per query.
inline const KernelSums& activeKernelSums() {
  const KernelSums* sums = activeKernelSumsTable.load(std::memory_order_acquire);
  return sums != nullptr ? *sums : firstKernelSums();
}

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

}  // namespace fastron::detail
