// Algorithm 1's passes over the training points for plain x86-64 (SSE2), or the target's baseline
// elsewhere: src/CMakeLists.txt gives this file its instruction set.
#define FASTRON_SIMD_NAMESPACE portable
#define FASTRON_SIMD_WIDTH 4
#include "gram_columns_impl.h"
