#pragma once
// The polynomial core of Cephes' sinf and cosf, for a float or a vector of floats (GCC's vector
// extension): the one copy of the constants behind the batched lanes' sinCos (simd_lanes.h) and
// the single float chain of the task-space features (geometry/control_points.cpp), so that both
// compute the same sines. Internal linkage, and nothing called from outside: code compiled once
// per SimdPath includes it (simd_lanes.h says why that matters).

namespace fastron::detail {
namespace {

/// 4 / pi: |x| times this, rounded up to an even integer, is the octant reducedSinCos expects.
constexpr float kFourOverPi = 1.27323954473516f;

/// sin and cos of |x| - octant pi/4, which lies in [-pi/4, pi/4], from a = |x| and the even
/// octant as a float: pi/4 subtracted in three steps (exact for |x| < 8192), then a polynomial
/// for each. The caller swaps and signs them by octant.
template <class F>
inline void reducedSinCos(F a, F octant, F& sine, F& cosine) {
  a = ((a - octant * 0.78515625f) - octant * 2.4187564849853515625e-4f) -
      octant * 3.77489497744594108e-8f;
  const F z = a * a;
  cosine =
      ((2.443315711809948e-5f * z - 1.388731625493765e-3f) * z + 4.166664568298827e-2f) * z * z -
      0.5f * z + 1.0f;
  sine = ((-1.9515295891e-4f * z + 8.3321608736e-3f) * z - 1.6666654611e-1f) * z * a + a;
}

}  // namespace
}  // namespace fastron::detail
