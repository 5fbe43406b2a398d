#pragma once
// The polynomial core of Cephes' sinf and cosf, for a float or a vector of floats (GCC's vector
// extension): the one copy of the constants behind the batched lanes' sinCos (simd_lanes.h) and
// the single float chain of the task-space features (geometry/point_kinematics.cpp), so that both
// compute the same sines; and that of Cephes' sin and cos for one double (geometry/sin_cos.h).
// Internal linkage, and nothing called from outside: code compiled once per SimdPath includes it
// (simd_lanes.h says why that matters).

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

/// The same for a double: Cephes' sin and cos, pi/4 subtracted in three steps (DP1-DP3, exact
/// far beyond any joint angle: geometry/sin_cos.h bounds it), then the polynomials of degree 6
/// in z, within about an ulp of the C library's. For the exact checkers' forward kinematics and
/// the training features (one angle at a time; no code compiled per SimdPath calls it).
inline void reducedSinCos(double a, double octant, double& sine, double& cosine) {
  a = ((a - octant * 7.85398125648498535156e-1) - octant * 3.77489470793079817668e-8) -
      octant * 2.69515142907905952645e-15;
  const double z = a * a;
  double c = -1.13585365213876817300e-11;
  c = c * z + 2.08757008419747316778e-9;
  c = c * z - 2.75573141792967388112e-7;
  c = c * z + 2.48015872888517045348e-5;
  c = c * z - 1.38888888888730564116e-3;
  c = c * z + 4.16666666666665929218e-2;
  cosine = 1.0 - 0.5 * z + z * z * c;
  double s = 1.58962301576546568060e-10;
  s = s * z - 2.50507477628578072866e-8;
  s = s * z + 2.75573136213857245213e-6;
  s = s * z - 1.98412698295895385996e-4;
  s = s * z + 8.33333333332211858878e-3;
  s = s * z - 1.66666666666666307295e-1;
  sine = a + a * z * s;
}

}  // namespace
}  // namespace fastron::detail
