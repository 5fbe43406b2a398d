// The batched control-point positions for AVX-512 (F, BW, DQ, VL): src/CMakeLists.txt gives this
// file its instruction set.
#define FASTRON_SIMD_NAMESPACE avx512
#define FASTRON_SIMD_WIDTH 16
#include "lane_kinematics_impl.h"
