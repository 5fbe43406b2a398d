// The batched control-point positions for AVX2 and FMA: src/CMakeLists.txt gives this file its
// instruction set.
#define FASTRON_SIMD_NAMESPACE avx2
#define FASTRON_SIMD_WIDTH 8
#include "lane_kinematics_impl.h"
