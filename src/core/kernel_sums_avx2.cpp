// The kernel sums for AVX2 and FMA: src/CMakeLists.txt gives this file its instruction set.
#define FASTRON_SIMD_NAMESPACE avx2
#define FASTRON_SIMD_WIDTH 8
#include "kernel_sums_impl.h"
