#pragma once
// The two passes over the training points of each Algorithm 1 iteration (a Gram column; the F
// update with the search for the most negative margin), compiled once per SimdPath
// (gram_columns_portable.cpp, gram_columns_avx2.cpp, gram_columns_avx512.cpp) like the kernel
// sums. In double: see trainer.cpp. Private to core.

#include <cstddef>

#include "fastron/core/kernel.h"
#include "fastron/core/simd.h"

namespace fastron::detail {

struct GramPasses {
  /// k[j - from] = K(x_i, x_j) for the rows j in [from, rows); x is column-major, rows x
  /// features.
  void (*column)(const double* x, std::size_t rows, std::size_t features, std::size_t i,
                 std::size_t from, KernelType type, double gamma, double* k);
  /// f += delta k over n values, then the most negative margin y_j f_j (returned) and its index
  /// (the first one on ties, in *worst).
  double (*addAndFindWorst)(double* f, const double* y, std::size_t n, const double* k,
                            double delta, std::size_t* worst);
};

/// The passes of activeSimdPath().
const GramPasses& activeGramPasses();

namespace portable {
extern const GramPasses kGramPasses;
}
namespace avx2 {
extern const GramPasses kGramPasses;
}
namespace avx512 {
extern const GramPasses kGramPasses;
}

}  // namespace fastron::detail
