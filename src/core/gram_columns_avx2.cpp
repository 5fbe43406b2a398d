// Algorithm 1's passes over the training points for AVX2 and FMA: src/CMakeLists.txt gives this
// file its instruction set.
#define FASTRON_SIMD_NAMESPACE avx2
#define FASTRON_SIMD_WIDTH 8
#include "gram_columns_impl.h"
