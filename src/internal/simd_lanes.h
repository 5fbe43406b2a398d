// Vectors of floats and doubles for the code compiled once per SimdPath (core/kernel_sums_impl.h,
// core/gram_columns_impl.h, geometry/lane_kinematics_impl.h): the including file defines
// FASTRON_SIMD_WIDTH, the floats per register of its instruction set (4, 8 or 16), and includes
// this file once.
//
// Written with the compilers' vector extensions, not Eigen: every function here has internal
// linkage, so the three compilations cannot exchange code at link time. (Eigen's templates would
// be instantiated under the same names in the three objects, and the linker keeps one of each:
// an AVX-512 copy could then run on a processor without AVX-512.) For the same reason code built
// on these helpers calls no inline function from outside (none of the C++ standard library's).

#pragma once

#ifndef FASTRON_SIMD_WIDTH
#error "define FASTRON_SIMD_WIDTH before including simd_lanes.h"
#endif

#include <cstddef>
#include <utility>

#include "internal/cephes_sin_cos.h"
#if defined(__x86_64__)
#include <immintrin.h>  // its functions are inline-only (GCC) or static (Clang): nothing shared
#endif

namespace fastron::detail {
namespace {

// One register of floats. Vectors wider than the registers (sixteen floats on AVX2, say) would
// compile too, but the compiler keeps them in memory: four AVX2 queries per pass measured 7.5
// times slower than in registers of eight.
constexpr std::size_t kWidth = FASTRON_SIMD_WIDTH;
using Floats = float __attribute__((vector_size(FASTRON_SIMD_WIDTH * 4)));
using Ints = int __attribute__((vector_size(FASTRON_SIMD_WIDTH * 4)));
static_assert(sizeof(Floats) == kWidth * sizeof(float));
// One register of doubles (Algorithm 1 sums in double).
constexpr std::size_t kDoubles = FASTRON_SIMD_WIDTH / 2;
using Doubles = double __attribute__((vector_size(FASTRON_SIMD_WIDTH * 4)));

inline Floats load(const float* p) {
  Floats v;
  __builtin_memcpy(&v, p, sizeof v);  // an unaligned load (the support blocks are aligned)
  return v;
}
inline Doubles load(const double* p) {
  Doubles v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

/// value in every lane: one broadcast. (Written as Floats{} + value it would also add 0, which the
/// compiler must keep, -0 + 0 being +0; written lane by lane it became sixteen inserts.)
template <std::size_t... I>
inline Floats broadcast(float value, std::index_sequence<I...> /*lanes*/) {
  const Floats first = {value};
  return __builtin_shufflevector(first, first, (I * 0)...);
}
inline Floats splat(float value) {
  return broadcast(value, std::make_index_sequence<kWidth>{});
}

/// a * b + c, one rounding where the instruction set has fused multiply-adds. Explicit, because
/// these files compile with -ffp-contract=off: left to the compiler, one loop may fuse a product
/// that another leaves apart (Clang did, at -O1), and a batched score must equal the single one
/// bit for bit.
inline Floats mulAdd(Floats a, Floats b, Floats c) {
#if FASTRON_SIMD_WIDTH == 16 && defined(__AVX512F__)
  return reinterpret_cast<Floats>(_mm512_fmadd_ps(
      reinterpret_cast<__m512>(a), reinterpret_cast<__m512>(b), reinterpret_cast<__m512>(c)));
#elif FASTRON_SIMD_WIDTH == 8 && defined(__FMA__)
  return reinterpret_cast<Floats>(_mm256_fmadd_ps(
      reinterpret_cast<__m256>(a), reinterpret_cast<__m256>(b), reinterpret_cast<__m256>(c)));
#else
  return a * b + c;
#endif
}
inline Doubles mulAdd(Doubles a, Doubles b, Doubles c) {
#if FASTRON_SIMD_WIDTH == 16 && defined(__AVX512F__)
  return reinterpret_cast<Doubles>(_mm512_fmadd_pd(
      reinterpret_cast<__m512d>(a), reinterpret_cast<__m512d>(b), reinterpret_cast<__m512d>(c)));
#elif FASTRON_SIMD_WIDTH == 8 && defined(__FMA__)
  return reinterpret_cast<Doubles>(_mm256_fmadd_pd(
      reinterpret_cast<__m256d>(a), reinterpret_cast<__m256d>(b), reinterpret_cast<__m256d>(c)));
#else
  return a * b + c;
#endif
}
/// The same for one double (without FMA instructions __builtin_fma would call the C library).
inline double mulAdd(double a, double b, double c) {
#ifdef __FMA__
  return __builtin_fma(a, b, c);
#else
  return a * b + c;
#endif
}
/// The same for one float.
inline float mulAdd(float a, float b, float c) {
#ifdef __FMA__
  return __builtin_fmaf(a, b, c);
#else
  return a * b + c;
#endif
}
inline Floats lanesOf(Floats v) {
  return v;
}
inline Floats lanesOf(float value) {
  return splat(value);
}
/// The same with a number for b or c, in every lane.
template <class B, class C>
inline Floats mulAdd(Floats a, B b, C c) {
  return mulAdd(a, lanesOf(b), lanesOf(c));
}

/// The sum of the lanes, adding the upper half of the vector to the lower half until one lane
/// is left (in registers: through memory, single queries at |S| 100 were 8 ns slower). The same
/// order for single and grouped sums, so their scores are the same numbers.
template <class V, std::size_t... I>
inline auto foldedInHalf(V v, std::index_sequence<I...> /*lower half*/) {
  return __builtin_shufflevector(v, v, I...) + __builtin_shufflevector(v, v, (I + sizeof...(I))...);
}

template <class V>
inline float laneSum(V v) {
  constexpr std::size_t kLanesOfV = sizeof(V) / sizeof(float);
  if constexpr (kLanesOfV == 1) {
    return v[0];
  } else {
    return laneSum(foldedInHalf(v, std::make_index_sequence<kLanesOfV / 2>{}));
  }
}

/// exp(x) for x <= 0 (Cephes' expf: x = n ln 2 + r with |r| <= ln 2 / 2, a degree-6 polynomial
/// for exp(r), 2^n from the exponent bits); about 2 ulp. Below exp(-87), where 2^n would leave
/// float's normal range, it stays at exp(-87) = 1.6e-38.
inline Floats expOfNonPositive(Floats x) {
  constexpr float kLowest = -87.0f;
  x = x < kLowest ? splat(kLowest) : x;
  // Round to nearest: x * log2(e) <= 0, so truncating it minus a half rounds it.
  const Ints n = __builtin_convertvector(x * 1.44269504088896341f - 0.5f, Ints);
  const Floats nf = __builtin_convertvector(n, Floats);
  const Floats r = mulAdd(nf, 2.12194440e-4f, mulAdd(nf, -0.693359375f, x));
  Floats p = splat(1.9875691500e-4f);
  p = mulAdd(p, r, 1.3981999507e-3f);
  p = mulAdd(p, r, 8.3334519073e-3f);
  p = mulAdd(p, r, 4.1665795894e-2f);
  p = mulAdd(p, r, 1.6666665459e-1f);
  p = mulAdd(p, r, 5.0000001201e-1f);
  const Floats e = mulAdd(p, r * r, r + 1.0f);
  return e * reinterpret_cast<Floats>((n + 127) << 23);
}

/// sin(x) and cos(x) of every lane, |x| < 8192 (Cephes' sinf and cosf: x reduced to
/// [-pi/4, pi/4] in three steps, then a polynomial for each; about 2 ulp).
inline void sinCos(Floats x, Floats& sine, Floats& cosine) {
  constexpr int kSignBit = -2147483647 - 1;
  const Ints signOfX = reinterpret_cast<Ints>(x) & kSignBit;
  const Floats a = reinterpret_cast<Floats>(reinterpret_cast<Ints>(x) & ~kSignBit);  // |x|
  Ints octant = __builtin_convertvector(a * kFourOverPi, Ints);                      // |x| / (pi/4)
  octant = (octant + 1) & ~1;
  Floats sinOfA, cosOfA;
  reducedSinCos(a, __builtin_convertvector(octant, Floats), sinOfA, cosOfA);
  const Ints swap = (octant & 2) != 0;  // the octants where sine follows the cosine's curve
  const Floats s = swap ? cosOfA : sinOfA, c = swap ? sinOfA : cosOfA;
  const Ints sinSign = (((octant & 4) != 0) & kSignBit) ^ signOfX;
  const Ints cosSign = ((((octant + 2) & 4) != 0) & kSignBit);
  sine = reinterpret_cast<Floats>(reinterpret_cast<Ints>(s) ^ sinSign);
  cosine = reinterpret_cast<Floats>(reinterpret_cast<Ints>(c) ^ cosSign);
}

}  // namespace
}  // namespace fastron::detail
