// The float kernel sums, written once and compiled once per SimdPath: each kernel_sums_*.cpp
// defines FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH (floats per register: 4, 8 or 16) and
// includes this file with its own -march flags.
//
// Written with the compilers' vector extensions, not Eigen: every function here has internal
// linkage, so the three compilations cannot exchange code at link time. (Eigen's templates would
// be instantiated under the same names in the three objects, and the linker keeps one of each:
// an AVX-512 copy could then run on a processor without AVX-512.) For the same reason nothing
// here calls a function of the C++ standard library.
//
// No include guard: included once per translation unit.

#if !defined(FASTRON_SIMD_NAMESPACE) || !defined(FASTRON_SIMD_WIDTH)
#error "define FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH before including kernel_sums_impl.h"
#endif

#include <cstddef>
#include <utility>

#include "kernel_sums.h"

namespace fastron::detail {
namespace {

// One register of floats. Vectors wider than the registers (sixteen floats on AVX2, say) would
// compile too, but the compiler keeps them in memory: four AVX2 queries per pass measured 7.5
// times slower than in registers of eight.
constexpr std::size_t kWidth = FASTRON_SIMD_WIDTH;
using Floats = float __attribute__((vector_size(FASTRON_SIMD_WIDTH * 4)));
using Ints = int __attribute__((vector_size(FASTRON_SIMD_WIDTH * 4)));
static_assert(sizeof(Floats) == kWidth * sizeof(float) && kSupportLanes % kWidth == 0);

inline Floats load(const float* p) {
  Floats v;
  __builtin_memcpy(&v, p, sizeof v);  // an unaligned load (the support blocks are aligned)
  return v;
}

inline Floats splat(float value) {
  return Floats{} + value;
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
  const Floats r = x - nf * 0.693359375f + nf * 2.12194440e-4f;
  Floats p = splat(1.9875691500e-4f);
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  const Floats e = p * (r * r) + r + 1.0f;
  return e * reinterpret_cast<Floats>((n + 127) << 23);
}

template <KernelType type>
inline Floats kernelOf(Floats r2, float gamma) {
  if constexpr (type == KernelType::RationalQuadratic) {
    const Floats t = 1.0f + (0.5f * gamma) * r2;  // the formula of kernelOfSquaredDistance
    return 1.0f / (t * t);
  } else {
    return expOfNonPositive(-gamma * r2);
  }
}

// From this many features on, r^2 is summed in two chains (even and odd features) instead of
// one: the chain of dependent multiply-adds per block is half as long, so more blocks are in
// flight at once (task-space batches of 16 at |S| 300 1.1x faster, single queries from within
// noise to 1.2x; at d = 2 and 4 the split measured 0.7-0.9x). Single and grouped sums split
// alike, so that their scores are the same numbers (Model.EveryDimensionScoresAlikeOnEveryPath).
constexpr std::size_t kPairedFrom = 6;

/// The kernel sum over the support set for one query; the dimension is D when D is not 0 (known
/// at compile time, the loop over features unrolls into straight code: 1.2 to 1.7 times faster
/// single queries at d = 7 and 12).
template <KernelType type, std::size_t D, bool paired>
float sumOne(const SupportView& s, const float* x) {
  const std::size_t dim = D != 0 ? D : s.dim;
  Floats sum = {};
  for (std::size_t b = 0; b < s.padded; b += kWidth) {
    Floats r2 = {}, odd = {};
    std::size_t j = 0;
    for (; paired && j + 1 < dim; j += 2) {
      const Floats d0 = load(s.soa + j * s.padded + b) - x[j];
      const Floats d1 = load(s.soa + (j + 1) * s.padded + b) - x[j + 1];
      r2 += d0 * d0;
      odd += d1 * d1;
    }
    for (; j < dim; ++j) {
      const Floats d0 = load(s.soa + j * s.padded + b) - x[j];
      r2 += d0 * d0;
    }
    if constexpr (paired) r2 += odd;
    sum += load(s.weights + b) * kernelOf<type>(r2, s.gamma);
  }
  return laneSum(sum);
}

/// Four kernel sums in one pass over the support set: each block of support coordinates is
/// loaded once for all four (the batch and edge queries of motion planning). The dimension stays
/// a run-time value here: unrolled over the features, four queries at a time measured 1.1-1.7
/// times slower.
template <KernelType type, bool paired>
void sumFour(const SupportView& s, const float* xs, float* out) {
  constexpr std::size_t kQ = kQueriesPerPass;
  const std::size_t dim = s.dim;
  Floats sums[kQ] = {};
  for (std::size_t b = 0; b < s.padded; b += kWidth) {
    Floats r2[kQ] = {}, odd[kQ] = {};
    std::size_t j = 0;
    for (; paired && j + 1 < dim; j += 2) {
      const Floats c0 = load(s.soa + j * s.padded + b);
      const Floats c1 = load(s.soa + (j + 1) * s.padded + b);
      for (std::size_t q = 0; q < kQ; ++q) {
        const Floats d0 = c0 - xs[q * dim + j], d1 = c1 - xs[q * dim + j + 1];
        r2[q] += d0 * d0;
        odd[q] += d1 * d1;
      }
    }
    for (; j < dim; ++j) {
      const Floats c = load(s.soa + j * s.padded + b);
      for (std::size_t q = 0; q < kQ; ++q) {
        const Floats d0 = c - xs[q * dim + j];
        r2[q] += d0 * d0;
      }
    }
    const Floats w = load(s.weights + b);
    for (std::size_t q = 0; q < kQ; ++q) {
      if constexpr (paired) r2[q] += odd[q];
      sums[q] += w * kernelOf<type>(r2[q], s.gamma);
    }
  }
  for (std::size_t q = 0; q < kQ; ++q) out[q] = laneSum(sums[q]);
}

template <KernelType type, bool paired>
float oneOfShape(const SupportView& s, const float* x) {
  // The feature dimensions of planar tests, 6- and 7-joint arms and 3- and 4-point task spaces.
  switch (s.dim) {
    case 2:
      return sumOne<type, 2, paired>(s, x);
    case 6:
      return sumOne<type, 6, paired>(s, x);
    case 7:
      return sumOne<type, 7, paired>(s, x);
    case 9:
      return sumOne<type, 9, paired>(s, x);
    case 12:
      return sumOne<type, 12, paired>(s, x);
    default:
      return sumOne<type, 0, paired>(s, x);
  }
}

template <KernelType type>
float oneOfKernel(const SupportView& s, const float* x) {
  return s.dim >= kPairedFrom ? oneOfShape<type, true>(s, x) : oneOfShape<type, false>(s, x);
}

float one(const SupportView& s, const float* x) {
  return s.type == KernelType::RationalQuadratic ? oneOfKernel<KernelType::RationalQuadratic>(s, x)
                                                 : oneOfKernel<KernelType::Gaussian>(s, x);
}

template <KernelType type>
void fourOfKernel(const SupportView& s, const float* xs, float* out) {
  if (s.dim >= kPairedFrom) {
    sumFour<type, true>(s, xs, out);
  } else {
    sumFour<type, false>(s, xs, out);
  }
}

void four(const SupportView& s, const float* xs, float* out) {
  if (s.type == KernelType::RationalQuadratic) {
    fourOfKernel<KernelType::RationalQuadratic>(s, xs, out);
  } else {
    fourOfKernel<KernelType::Gaussian>(s, xs, out);
  }
}

}  // namespace

namespace FASTRON_SIMD_NAMESPACE {
const KernelSums kKernelSums{&one, &four};
}

}  // namespace fastron::detail
