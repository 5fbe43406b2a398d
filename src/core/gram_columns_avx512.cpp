// Algorithm 1's passes over the training points for AVX-512 (F, BW, DQ, VL): src/CMakeLists.txt
// gives this file its instruction set.
#define FASTRON_SIMD_NAMESPACE avx512
#define FASTRON_SIMD_WIDTH 16
#include "gram_columns_impl.h"
