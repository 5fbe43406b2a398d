// The float kernel sums, written once and compiled once per SimdPath: each kernel_sums_*.cpp
// defines FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH (floats per register: 4, 8 or 16) and
// includes this file with its own -march flags.
//
// Written with the vector helpers of simd_lanes.h (which says why not with Eigen).
//
// No include guard: included once per translation unit.

#if !defined(FASTRON_SIMD_NAMESPACE) || !defined(FASTRON_SIMD_WIDTH)
#error "define FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH before including kernel_sums_impl.h"
#endif

#include <cstddef>

#include "internal/simd_lanes.h"
#include "kernel_sums.h"

namespace fastron::detail {
namespace {

static_assert(kSupportLanes % kWidth == 0);

template <KernelType type>
inline Floats kernelOf(Floats r2, float gamma) {
  if constexpr (type == KernelType::RationalQuadratic) {
    const Floats t = mulAdd(r2, 0.5f * gamma, 1.0f);  // the formula of kernelOfSquaredDistance
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
      r2 = mulAdd(d0, d0, r2);
      odd = mulAdd(d1, d1, odd);
    }
    for (; j < dim; ++j) {
      const Floats d0 = load(s.soa + j * s.padded + b) - x[j];
      r2 = mulAdd(d0, d0, r2);
    }
    if constexpr (paired) r2 += odd;
    sum = mulAdd(load(s.weights + b), kernelOf<type>(r2, s.gamma), sum);
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
        r2[q] = mulAdd(d0, d0, r2[q]);
        odd[q] = mulAdd(d1, d1, odd[q]);
      }
    }
    for (; j < dim; ++j) {
      const Floats c = load(s.soa + j * s.padded + b);
      for (std::size_t q = 0; q < kQ; ++q) {
        const Floats d0 = c - xs[q * dim + j];
        r2[q] = mulAdd(d0, d0, r2[q]);
      }
    }
    const Floats w = load(s.weights + b);
    for (std::size_t q = 0; q < kQ; ++q) {
      if constexpr (paired) r2[q] += odd[q];
      sums[q] = mulAdd(w, kernelOf<type>(r2[q], s.gamma), sums[q]);
    }
  }
  for (std::size_t q = 0; q < kQ; ++q) out[q] = laneSum(sums[q]);
}

/// The kernel sum for one query when the kernel has point terms (B = 3: a control point each;
/// 0: s.block at run time; D as in sumOne): the blocks of a register of support points are
/// independent chains. Two sums are kept, of w k(whole) and of w (sum of the point terms), and
/// weighted once at the end.
template <KernelType type, std::size_t D, std::size_t B>
float sumOneOfPoints(const SupportView& s, const float* x) {
  const std::size_t dim = D != 0 ? D : s.dim;
  const std::size_t block = B != 0 ? B : s.block;
  Floats wholeSum = {}, pointSum = {};
  for (std::size_t b = 0; b < s.padded; b += kWidth) {
    Floats whole = {}, points = {};
    for (std::size_t g = 0; g < dim; g += block) {
      Floats r2 = {};
      for (std::size_t c = g; c < g + block; ++c) {
        const Floats d = load(s.soa + c * s.padded + b) - x[c];
        r2 = mulAdd(d, d, r2);
      }
      whole += r2;
      points += kernelOf<type>(r2, s.gamma);
    }
    const Floats w = load(s.weights + b);
    wholeSum = mulAdd(w, kernelOf<type>(whole, s.gamma), wholeSum);
    pointSum = mulAdd(w, points, pointSum);
  }
  return s.wholeWeight * laneSum(wholeSum) + s.pointWeight * laneSum(pointSum);
}

/// sumFour for a kernel with point terms: each score equals sumOneOfPoints of the same vector.
template <KernelType type>
void sumFourOfPoints(const SupportView& s, const float* xs, float* out) {
  constexpr std::size_t kQ = kQueriesPerPass;
  const std::size_t dim = s.dim, block = s.block;
  Floats wholeSums[kQ] = {}, pointSums[kQ] = {};
  for (std::size_t b = 0; b < s.padded; b += kWidth) {
    Floats whole[kQ] = {}, points[kQ] = {};
    for (std::size_t g = 0; g < dim; g += block) {
      Floats r2[kQ] = {};
      for (std::size_t c = g; c < g + block; ++c) {
        const Floats coordinate = load(s.soa + c * s.padded + b);
        for (std::size_t q = 0; q < kQ; ++q) {
          const Floats d = coordinate - xs[q * dim + c];
          r2[q] = mulAdd(d, d, r2[q]);
        }
      }
      for (std::size_t q = 0; q < kQ; ++q) {
        whole[q] += r2[q];
        points[q] += kernelOf<type>(r2[q], s.gamma);
      }
    }
    const Floats w = load(s.weights + b);
    for (std::size_t q = 0; q < kQ; ++q) {
      wholeSums[q] = mulAdd(w, kernelOf<type>(whole[q], s.gamma), wholeSums[q]);
      pointSums[q] = mulAdd(w, points[q], pointSums[q]);
    }
  }
  for (std::size_t q = 0; q < kQ; ++q) {
    out[q] = s.wholeWeight * laneSum(wholeSums[q]) + s.pointWeight * laneSum(pointSums[q]);
  }
}

template <KernelType type>
float oneOfPoints(const SupportView& s, const float* x) {
  // Three and four control points, unrolled (Baxter, |S| 250: 182-186 ns a query against
  // 223-230 ns with the loops' bounds at run time).
  if (s.block == 3 && s.dim == 9) return sumOneOfPoints<type, 9, 3>(s, x);
  if (s.block == 3 && s.dim == 12) return sumOneOfPoints<type, 12, 3>(s, x);
  if (s.block == 3) return sumOneOfPoints<type, 0, 3>(s, x);
  return sumOneOfPoints<type, 0, 0>(s, x);
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
  if (s.block != 0) return oneOfPoints<type>(s, x);
  return s.dim >= kPairedFrom ? oneOfShape<type, true>(s, x) : oneOfShape<type, false>(s, x);
}

float one(const SupportView& s, const float* x) {
  return s.type == KernelType::RationalQuadratic ? oneOfKernel<KernelType::RationalQuadratic>(s, x)
                                                 : oneOfKernel<KernelType::Gaussian>(s, x);
}

/// k(r2) and dk/dr2 of every lane: for the rational quadratic one reciprocal of t serves both
/// (k = t^-2, k' = -gamma t^-3).
template <KernelType type>
inline void kernelAndDerivative(Floats r2, float gamma, Floats& k, Floats& derivative) {
  if constexpr (type == KernelType::RationalQuadratic) {
    const Floats inverse = 1.0f / mulAdd(r2, 0.5f * gamma, 1.0f);
    k = inverse * inverse;
    derivative = (-gamma * k) * inverse;
  } else {
    k = expOfNonPositive(-gamma * r2);
    derivative = -gamma * k;
  }
}

/// f of one feature vector x and its gradient with respect to x (dim floats to dfdx), the kernel
/// with point terms (B and D as in sumOneOfPoints): d/dx_c of w (W k(whole) + P sum_g k(r2_g)) is
/// 2 w (W k'(whole) + P k'(r2 of c's block)) (x_c - s_c). Each feature's terms are summed per
/// lane, as the scores are.
template <KernelType type, std::size_t D, std::size_t B>
float gradientOfPoints(const SupportView& s, const float* x, float* dfdx) {
  const std::size_t dim = D != 0 ? D : s.dim;
  const std::size_t block = B != 0 ? B : s.block;
  constexpr std::size_t kFeatures = D != 0 ? D : kMaxFeatures;
  constexpr std::size_t kBlocks = D != 0 && B != 0 ? D / B : kMaxFeatures;
  const float twoW = 2 * s.wholeWeight, twoP = 2 * s.pointWeight;
  Floats wholeSum = {}, pointSum = {}, slopes[kFeatures] = {};  // slopes: sum of coef (s_c - x_c)
  for (std::size_t b = 0; b < s.padded; b += kWidth) {
    Floats r2OfBlock[kBlocks], whole = {}, points = {}, k, derivative;
    for (std::size_t g = 0; g < dim / block; ++g) {
      Floats r2 = {};
      for (std::size_t c = g * block; c < (g + 1) * block; ++c) {
        const Floats d = load(s.soa + c * s.padded + b) - x[c];
        r2 = mulAdd(d, d, r2);
      }
      r2OfBlock[g] = r2;
      whole += r2;
    }
    const Floats w = load(s.weights + b);
    kernelAndDerivative<type>(whole, s.gamma, k, derivative);
    wholeSum = mulAdd(w, k, wholeSum);
    const Floats wholeCoefficient = (twoW * w) * derivative;
    for (std::size_t g = 0; g < dim / block; ++g) {
      kernelAndDerivative<type>(r2OfBlock[g], s.gamma, k, derivative);
      points += k;
      const Floats coefficient = mulAdd(twoP * w, derivative, wholeCoefficient);
      for (std::size_t c = g * block; c < (g + 1) * block; ++c)
        slopes[c] = mulAdd(coefficient, load(s.soa + c * s.padded + b) - x[c], slopes[c]);
    }
    pointSum = mulAdd(w, points, pointSum);
  }
  for (std::size_t c = 0; c < dim; ++c) dfdx[c] = -laneSum(slopes[c]);
  return s.wholeWeight * laneSum(wholeSum) + s.pointWeight * laneSum(pointSum);
}

/// The same for the one-term kernel: d/dx_c of w k(|x - s|^2) is 2 w k'(|x - s|^2) (x_c - s_c).
template <KernelType type, std::size_t D>
float gradientOfOne(const SupportView& s, const float* x, float* dfdx) {
  const std::size_t dim = D != 0 ? D : s.dim;
  constexpr std::size_t kFeatures = D != 0 ? D : kMaxFeatures;
  Floats sum = {}, slopes[kFeatures] = {};
  for (std::size_t b = 0; b < s.padded; b += kWidth) {
    Floats r2 = {}, k, derivative;
    for (std::size_t c = 0; c < dim; ++c) {
      const Floats d = load(s.soa + c * s.padded + b) - x[c];
      r2 = mulAdd(d, d, r2);
    }
    const Floats w = load(s.weights + b);
    kernelAndDerivative<type>(r2, s.gamma, k, derivative);
    sum = mulAdd(w, k, sum);
    const Floats coefficient = (2.0f * w) * derivative;
    for (std::size_t c = 0; c < dim; ++c)
      slopes[c] = mulAdd(coefficient, load(s.soa + c * s.padded + b) - x[c], slopes[c]);
  }
  for (std::size_t c = 0; c < dim; ++c) dfdx[c] = -laneSum(slopes[c]);
  return laneSum(sum);
}

template <KernelType type>
float gradientOfKernel(const SupportView& s, const float* x, float* dfdx) {
  if (s.block == 3 && s.dim == 9) return gradientOfPoints<type, 9, 3>(s, x, dfdx);
  if (s.block == 3 && s.dim == 12) return gradientOfPoints<type, 12, 3>(s, x, dfdx);
  if (s.block != 0) return gradientOfPoints<type, 0, 0>(s, x, dfdx);
  switch (s.dim) {
    case 2:
      return gradientOfOne<type, 2>(s, x, dfdx);
    case 7:
      return gradientOfOne<type, 7>(s, x, dfdx);
    case 12:
      return gradientOfOne<type, 12>(s, x, dfdx);
    default:
      return gradientOfOne<type, 0>(s, x, dfdx);
  }
}

float gradient(const SupportView& s, const float* x, float* dfdx) {
  return s.type == KernelType::RationalQuadratic
             ? gradientOfKernel<KernelType::RationalQuadratic>(s, x, dfdx)
             : gradientOfKernel<KernelType::Gaussian>(s, x, dfdx);
}

template <KernelType type>
void fourOfKernel(const SupportView& s, const float* xs, float* out) {
  if (s.block != 0) {
    sumFourOfPoints<type>(s, xs, out);
  } else if (s.dim >= kPairedFrom) {
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
const KernelSums kKernelSums{&one, &four, &gradient};
}

}  // namespace fastron::detail
