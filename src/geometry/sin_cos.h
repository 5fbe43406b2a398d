#pragma once
// The sine and cosine of one joint angle without a branch, in float (the single chain of the
// task-space features) or in double (the exact checkers' forward kinematics, kinematics.cpp, and
// the training features): Cephes' polynomials (core/cephes_sin_cos.h), the octant's swap and
// signs applied with bit operations. The C library's sinf / cosf and sincos branch on the angle's
// range, which a planner's random configurations mispredict (docs/performance.md, "Sine and
// cosine without a branch" and "Forward kinematics of the exact checkers").

#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "internal/cephes_sin_cos.h"

namespace fastron::detail {

/// Beyond this |x| the reduction by pi/4 in three steps loses digits (float) or may (double, far
/// beyond any joint angle), and the C library takes over.
template <class Real>
inline constexpr Real kReducibleAngle = std::is_same_v<Real, float> ? Real(8192) : Real(1e6);

/// sin(x) and cos(x) for a float or a double, within an ulp or two of the C library's (tested:
/// ControlPoints.FloatPositionsHoldAtOctantBoundariesAndLargeAngles and
/// ForwardKinematics.AJointTurnsAsEigensAngleAxisDoes).
template <class Real>
inline void sinCos(Real x, Real& sine, Real& cosine) {
  using Bits = std::conditional_t<std::is_same_v<Real, float>, std::uint32_t, std::uint64_t>;
  constexpr int kSignShift = 8 * sizeof(Real) - 3;  // octant bit 2 to the sign bit
  constexpr Bits kSignBit = Bits{1} << (8 * sizeof(Real) - 1);
  const Real a = std::fabs(x);
  if (!(a <= kReducibleAngle<Real>)) {  // NaN too
    sine = std::sin(x);
    cosine = std::cos(x);
    return;
  }
  // The even octant nearest |x| / (pi/4), as Cephes rounds it; in float with the lanes' 4 / pi,
  // so that the single chain and the batch compute the same sines.
  constexpr Real fourOverPi =
      std::is_same_v<Real, float> ? Real(kFourOverPi) : Real(1.27323954473516268615);
  const Bits octant = (static_cast<Bits>(a * fourOverPi) + 1u) & ~Bits{1};
  Real sinOfA = 0, cosOfA = 0;
  reducedSinCos(a, static_cast<Real>(octant), sinOfA, cosOfA);
  // With ?: GCC emitted jumps: the float features took 124 ns against 65 ns.
  const Bits swap = Bits{0} - ((octant >> 1) & 1u);  // all ones where sine follows cosine
  const auto sinBits = std::bit_cast<Bits>(sinOfA);
  const auto cosBits = std::bit_cast<Bits>(cosOfA);
  const Bits sinSign = ((octant & 4u) << kSignShift) ^ (std::bit_cast<Bits>(x) & kSignBit);
  const Bits cosSign = ((octant + 2u) & 4u) << kSignShift;
  sine = std::bit_cast<Real>(((sinBits & ~swap) | (cosBits & swap)) ^ sinSign);
  cosine = std::bit_cast<Real>(((cosBits & ~swap) | (sinBits & swap)) ^ cosSign);
}

}  // namespace fastron::detail
