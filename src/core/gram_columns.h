#pragma once
// The two passes over the training points of each Algorithm 1 iteration (a Gram column; the F
// update with the search for the most negative margin), compiled once per SimdPath
// (gram_columns_portable.cpp, gram_columns_avx2.cpp, gram_columns_avx512.cpp) like the kernel
// sums. Summed in double: see trainer.cpp. Private to core.

#include <cstddef>

#include "fastron/core/kernel.h"
#include "simd_dispatch.h"

namespace fastron::detail {

/// The most features a training point has (kMaxFeatureDimension of feature_map.h, which
/// trainer.cpp checks; this header stays free of Eigen for the files compiled per path).
inline constexpr std::size_t kMaxGramFeatures = 192;

/// The kernel as the passes read it: plain values, because the code compiled per path calls no
/// inline function from outside (simd_lanes.h says why), Kernel's members included.
struct GramKernel {
  KernelType type = KernelType::RationalQuadratic;
  double gamma = 1;
  std::size_t block = 0;  ///< features per point term (Kernel::block); 0: one term
  double wholeWeight = 1, pointWeight = 0;  ///< Kernel::wholeWeight(), pointWeight(features)
};

struct GramPasses {
  /// k[j - from] = K(x_i, x_j) for the rows j in [from, to); x is column-major, rows x
  /// features, and xf the same values as floats (a Trainer's features are rounded to float):
  /// which one is read depends on the number of features (gram_columns_impl.h); each float is
  /// widened to double before any arithmetic, so the column is the same either way. The kernel's
  /// block divides `features` (validated by the Trainer). A value does not depend on `from` and
  /// `to`: a column computed in pieces equals the column computed at once.
  void (*column)(const double* x, const float* xf, std::size_t rows, std::size_t features,
                 std::size_t i, std::size_t from, std::size_t to, const GramKernel& kernel,
                 double* k);
  /// f[j - from] += sum_s weights[s] K(support_s, x_j) for the rows j in [from, to) of x
  /// (column-major, rows x features) and the `count` rows of `support` (row-major, count x
  /// features): the hypothesis of new training points from the current weights, summed in the
  /// order of s.
  void (*addSums)(const double* support, const double* weights, std::size_t count, const double* x,
                  std::size_t rows, std::size_t features, std::size_t from, std::size_t to,
                  const GramKernel& kernel, double* f);
  /// f += delta k over n values, then the most negative margin y_j f_j (returned) and its index
  /// (the first one on ties, in *worst).
  double (*addAndFindWorst)(double* f, const double* y, std::size_t n, const double* k,
                            double delta, std::size_t* worst);
};

namespace portable {
extern const GramPasses kGramPasses;
}
namespace avx2 {
extern const GramPasses kGramPasses;
}
namespace avx512 {
extern const GramPasses kGramPasses;
}

/// The passes of the path in use.
inline const GramPasses& activeGramPasses() {
  return ofSimdPath(currentSimdPath(), portable::kGramPasses, avx2::kGramPasses,
                    avx512::kGramPasses);
}

}  // namespace fastron::detail
