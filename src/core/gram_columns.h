#pragma once
// The two passes over the training points of each Algorithm 1 iteration (a Gram column; the F
// update with the search for the most negative margin), compiled once per SimdPath
// (gram_columns_portable.cpp, gram_columns_avx2.cpp, gram_columns_avx512.cpp) like the kernel
// sums. F is summed in double, and a column is double or, for TrainParams::floatGramColumns, float
// within a bound (see trainer.cpp). Private to core.

#include <cstddef>

#include "fastron/core/kernel.h"
#include "internal/simd_dispatch.h"

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

/// A bound on |k - K| for every value k of columnInFloat, K being the exact kernel of the same
/// (float) features, in units of float's rounding unit u = 2^-24. Per term of b coordinates: the
/// differences, squares and fused sums give r2 within (b + 2) u relative (all terms positive), the
/// whole vector's r2 adds one rounding per block; gamma / 2 is rounded to float (u). The term
/// (1 + x)^-2 of x = gamma r2 / 2 moves by at most max 2x / (1 + x)^3 = 0.3 times x's relative
/// error, and its own evaluation (a fused 1 + x, a product, a division) adds 4 u. The weighted
/// sum of the terms adds (terms + 4) u of the kernel's largest value, wholeWeight + pointWeight
/// times the terms. Doubled: for second-order terms and the SSE2 path, which rounds each product
/// and sum of a multiply-add apart.
inline double floatColumnError(const GramKernel& kernel, std::size_t features) {
  constexpr double u = 0x1p-24;
  const std::size_t terms = kernel.block == 0 ? 0 : features / kernel.block;
  const std::size_t block = kernel.block == 0 ? features : kernel.block;
  const auto termError = [&](double relative) { return 0.3 * (relative + u) + 4 * u; };
  const double wholeRelative = static_cast<double>(block + 3 + terms) * u;
  const double pointRelative = static_cast<double>(block + 3) * u;
  const double wholeWeight = kernel.block == 0 ? 1 : kernel.wholeWeight;
  const double pointWeight = kernel.block == 0 ? 0 : kernel.pointWeight;
  const double largest = wholeWeight + pointWeight * static_cast<double>(terms);
  return 2 * (wholeWeight * termError(wholeRelative) +
              pointWeight * static_cast<double>(terms) * termError(pointRelative) +
              static_cast<double>(terms + 4) * u * largest);
}

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
  /// The same column of a rational-quadratic kernel computed in float from xf (column-major,
  /// rows x features), each value within floatColumnError(kernel, features) of the exact kernel
  /// of the same features, and depending on its row alone. For TrainParams::floatGramColumns:
  /// sixteen rows per AVX-512 register instead of eight (docs/performance.md, "Float Gram columns
  /// with exact signs").
  void (*columnInFloat)(const float* xf, std::size_t rows, std::size_t features, std::size_t i,
                        std::size_t from, std::size_t to, const GramKernel& kernel, double* k);
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
