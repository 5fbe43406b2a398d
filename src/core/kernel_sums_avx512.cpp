// The kernel sums for AVX-512 (F, BW, DQ, VL): src/CMakeLists.txt gives this file its instruction
// set.
#define FASTRON_SIMD_NAMESPACE avx512
#define FASTRON_SIMD_WIDTH 16
#include "kernel_sums_impl.h"
