// The passes of Algorithm 1 over the training points, written once and compiled once per SimdPath:
// each gram_columns_*.cpp defines FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH and includes this
// file with its own -march flags. Written with the vector helpers of simd_lanes.h (which says why
// not with Eigen); the C library's exp is the one function called from outside.
//
// No include guard: included once per translation unit.

#if !defined(FASTRON_SIMD_NAMESPACE) || !defined(FASTRON_SIMD_WIDTH)
#error "define FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH before including gram_columns_impl.h"
#endif

#include <cstddef>

#include "gram_columns.h"
#include "internal/simd_lanes.h"

namespace fastron::detail {
namespace {

/// The kernel of one term from its squared distance (the formulas of kernelOfSquaredDistance).
inline double termOf(double r2, bool rationalQuadratic, double gamma) {
  if (rationalQuadratic) {
    const double t = mulAdd(0.5 * gamma, r2, 1);
    return 1 / (t * t);
  }
  return __builtin_exp(-gamma * r2);
}

/// The kernel of two points from their differences difference(c), c < features, in the order of
/// Kernel::between, with multiply-adds: the scalar form of every path below.
template <class Difference>
inline double kernelOfDifferences(const Difference& difference, std::size_t features,
                                  const GramKernel& kernel) {
  const bool rationalQuadratic = kernel.type == KernelType::RationalQuadratic;
  const std::size_t block = kernel.block == 0 ? features : kernel.block;
  double whole = 0, points = 0;
  for (std::size_t g = 0; g < features; g += block) {
    double r2 = 0;
    for (std::size_t c = g; c < g + block; ++c) {
      const double t = difference(c);
      r2 = mulAdd(t, t, r2);
    }
    whole += r2;
    if (kernel.block != 0) points += termOf(r2, rationalQuadratic, kernel.gamma);
  }
  if (kernel.block == 0) return termOf(whole, rationalQuadratic, kernel.gamma);
  return kernel.wholeWeight * termOf(whole, rationalQuadratic, kernel.gamma) +
         kernel.pointWeight * points;
}

/// K(x_i, x_j) of one row j of x (column-major, rows x features).
inline double entry(const double* x, std::size_t rows, std::size_t features, const double* xi,
                    std::size_t j, const GramKernel& kernel) {
  return kernelOfDifferences([&](std::size_t c) { return x[c * rows + j] - xi[c]; }, features,
                             kernel);
}

/// The rational-quadratic term of a register of squared distances.
inline Doubles termOf(Doubles r2, Doubles halfGammas) {
  const Doubles t = mulAdd(r2, halfGammas, 1 - Doubles{});  // x - 0 is x exactly
  return 1 / (t * t);
}

/// Few features: a register of rows at a time, every feature column adding to squared distances
/// held in a register, then the kernel: one store per register of rows. (Summing one feature
/// column at a time into a block of distances in L1 stored and reloaded them once per feature:
/// perf showed those stores as the column's cost.) Each value is computed as `entry` computes
/// it, so the result does not depend on where the registers start. A Gaussian kernel with point
/// terms goes row by row (an exponential per term; no planner uses it).
void columnByRow(const double* x, std::size_t rows, std::size_t features, std::size_t i,
                 std::size_t from, std::size_t to, const GramKernel& kernel, double* k) {
  const std::size_t n = to - from;
  double xi[kMaxGramFeatures];
  for (std::size_t c = 0; c < features; ++c) xi[c] = x[c * rows + i];
  const bool rationalQuadratic = kernel.type == KernelType::RationalQuadratic;
  const Doubles halfGammas = 0.5 * kernel.gamma - Doubles{};
  std::size_t j = 0;
  if (kernel.block == 0) {
    for (; j + kDoubles <= n; j += kDoubles) {
      Doubles r2 = {};
      for (std::size_t c = 0; c < features; ++c) {
        const Doubles t = load(x + c * rows + from + j) - xi[c];
        r2 = mulAdd(t, t, r2);
      }
      if (rationalQuadratic) r2 = termOf(r2, halfGammas);
      __builtin_memcpy(k + j, &r2, sizeof r2);
    }
    if (!rationalQuadratic) {  // the exponentials of the squared distances
      for (std::size_t m = 0; m < j; ++m) k[m] = __builtin_exp(-kernel.gamma * k[m]);
    }
  } else if (rationalQuadratic) {
    const Doubles wholeWeights = kernel.wholeWeight - Doubles{},
                  pointWeights = kernel.pointWeight - Doubles{};
    for (; j + kDoubles <= n; j += kDoubles) {
      Doubles whole = {}, points = {};
      for (std::size_t g = 0; g < features; g += kernel.block) {
        Doubles r2 = {};
        for (std::size_t c = g; c < g + kernel.block; ++c) {
          const Doubles t = load(x + c * rows + from + j) - xi[c];
          r2 = mulAdd(t, t, r2);
        }
        whole += r2;
        points += termOf(r2, halfGammas);
      }
      const Doubles value = wholeWeights * termOf(whole, halfGammas) + pointWeights * points;
      __builtin_memcpy(k + j, &value, sizeof value);
    }
  }
  for (; j < n; ++j) k[j] = entry(x, rows, features, xi, from + j, kernel);
}

// Many features (more than kRowFeatures): rows go in blocks whose squared distances stay in L1
// while every feature column adds to them (with 27 features, summing into the whole column
// instead moved it through the cache 27 times). The features are read as floats, half the bytes:
// N 8000 x 27 of them then stay in this machine's 1 MB L2 (d 18: 11.5 -> 9.5 ms, d 27: 22.2 ->
// 15.8 ms for all of Algorithm 1). Widened to double, each value is the double the Trainer holds.
constexpr std::size_t kBlock = 256;

/// One control point's rational-quadratic term for `size` rows from row `first`, in one pass over
/// its three feature columns g, g + 1, g + 2 (N 8000, d 18, share 1/3: all of Algorithm 1 in 13.2
/// ms against 20.5 ms in separate passes; d 27: 18.8 against 31.3): the squared distance to row i
/// added to `whole`, its term to `points`. In double (columnByFeature) or in float
/// (columnInFloatByFeature), each value from the float features as stored.
template <class Real>
void addControlPointTerms(const float* x, std::size_t rows, std::size_t g, std::size_t i,
                          std::size_t first, std::size_t size, Real halfGamma,
                          Real* __restrict whole, Real* __restrict points) {
  // __restrict: the sums are the caller's own arrays, which the feature columns never overlap (as
  // local arrays in the loop before, they vectorised without run-time overlap checks).
  const float* __restrict v0 = x + g * rows + first;
  const float* __restrict v1 = v0 + rows;
  const float* __restrict v2 = v1 + rows;
  const Real x0 = x[g * rows + i], x1 = x[(g + 1) * rows + i], x2 = x[(g + 2) * rows + i];
  for (std::size_t j = 0; j < size; ++j) {
    const Real t0 = Real(v0[j]) - x0, t1 = Real(v1[j]) - x1, t2 = Real(v2[j]) - x2;
    const Real d2 = mulAdd(t2, t2, mulAdd(t1, t1, mulAdd(t0, t0, Real(0))));
    whole[j] += d2;
    const Real t = mulAdd(halfGamma, d2, Real(1));
    points[j] += 1 / (t * t);
  }
}

/// The term of each of `size` squared distances, in place (one loop per kernel type, the formulas
/// of kernelOfSquaredDistance: a branch inside would stop the loop vectorising).
void termsInPlace(double* r2, std::size_t size, KernelType type, double gamma) {
  if (type == KernelType::RationalQuadratic) {
    const double halfGamma = 0.5 * gamma;
    for (std::size_t j = 0; j < size; ++j) {
      const double t = mulAdd(halfGamma, r2[j], 1);
      r2[j] = 1 / (t * t);
    }
  } else {
    for (std::size_t j = 0; j < size; ++j) r2[j] = __builtin_exp(-gamma * r2[j]);
  }
}

void columnByFeature(const float* x, std::size_t rows, std::size_t features, std::size_t i,
                     std::size_t from, std::size_t to, const GramKernel& kernel, double* k) {
  const std::size_t n = to - from;
  const std::size_t block = kernel.block == 0 ? features : kernel.block;
  for (std::size_t begin = 0; begin < n; begin += kBlock) {
    const std::size_t size = n - begin < kBlock ? n - begin : kBlock;
    double whole[kBlock], points[kBlock], r2[kBlock];
    for (std::size_t j = 0; j < size; ++j) whole[j] = points[j] = 0;
    for (std::size_t g = 0; g < features; g += block) {
      if (block == 3 && kernel.type == KernelType::RationalQuadratic) {
        addControlPointTerms(x, rows, g, i, from + begin, size, 0.5 * kernel.gamma, whole, points);
        continue;
      }
      for (std::size_t j = 0; j < size; ++j) r2[j] = 0;
      for (std::size_t c = g; c < g + block; ++c) {
        const float* values = x + c * rows + from + begin;
        const double xi = x[c * rows + i];
        for (std::size_t j = 0; j < size; ++j) {
          const double t = double(values[j]) - xi;
          r2[j] = mulAdd(t, t, r2[j]);
        }
      }
      for (std::size_t j = 0; j < size; ++j) whole[j] += r2[j];
      if (kernel.block != 0) {
        termsInPlace(r2, size, kernel.type, kernel.gamma);
        for (std::size_t j = 0; j < size; ++j) points[j] += r2[j];
      }
    }
    termsInPlace(whole, size, kernel.type, kernel.gamma);
    double* out = k + begin;
    if (kernel.block == 0) {
      for (std::size_t j = 0; j < size; ++j) out[j] = whole[j];
    } else {
      const double wholeWeight = kernel.wholeWeight, pointWeight = kernel.pointWeight;
      for (std::size_t j = 0; j < size; ++j)
        out[j] = wholeWeight * whole[j] + pointWeight * points[j];
    }
  }
}

// Up to this many features a Gram column goes a register of rows at a time (N 8000: d 7 2.98
// against 3.63 ms, d 9 3.95 against 4.00 ms for all of Algorithm 1), beyond it a feature at a
// time (d 18 10.3 against 10.7 ms, d 27 18.0 against 21.1 ms: more streams than the prefetchers
// follow). Both compute every value alike. The register path reads doubles: up to 12 features the
// points stay in L2 anyway, and reading floats measured 2.90-3.10 ms at d 7 against 2.73-2.82 ms
// with doubles (separate runs).
constexpr std::size_t kRowFeatures = 12;

void column(const double* x, const float* xf, std::size_t rows, std::size_t features, std::size_t i,
            std::size_t from, std::size_t to, const GramKernel& kernel, double* k) {
  if (features <= kRowFeatures) {
    columnByRow(x, rows, features, i, from, to, kernel, k);
  } else {
    columnByFeature(xf, rows, features, i, from, to, kernel, k);
  }
}

/// The rational-quadratic term of a register of squared distances, in float.
inline Floats termOf(Floats r2, Floats halfGammas) {
  const Floats t = mulAdd(r2, halfGammas, splat(1.0f));
  return 1 / (t * t);
}

/// A rational-quadratic Gram column in float of few features and one term
/// (TrainParams::floatGramColumns): a register of kWidth rows at a time, twice the rows of a double
/// register, from the float features. The last rows go through a padded register, so every value
/// is computed in a lane alike and depends on its row alone (the two cores' halves of an
/// iteration then give the column of one core).
void columnInFloatByRow(const float* x, std::size_t rows, std::size_t features, std::size_t i,
                        std::size_t from, std::size_t to, const GramKernel& kernel, double* k) {
  const std::size_t n = to - from;
  float xi[kMaxGramFeatures];
  for (std::size_t c = 0; c < features; ++c) xi[c] = x[c * rows + i];
  const Floats halfGammas = splat(static_cast<float>(0.5 * kernel.gamma));
  // The kernel of a register of rows whose feature c is feature(c).
  const auto valueOf = [&](const auto& feature) {
    Floats r2 = {};
    for (std::size_t c = 0; c < features; ++c) {
      const Floats t = feature(c) - splat(xi[c]);
      r2 = mulAdd(t, t, r2);
    }
    return termOf(r2, halfGammas);
  };
  std::size_t j = 0;
  for (; j + kWidth <= n; j += kWidth) {
    const Floats value = valueOf([&](std::size_t c) { return load(x + c * rows + from + j); });
    for (std::size_t l = 0; l < kWidth; ++l) k[j + l] = value[l];
  }
  if (j == n) return;
  float last[kMaxGramFeatures * kWidth];  // the last rows, then copies of x_i
  for (std::size_t c = 0; c < features; ++c) {
    for (std::size_t l = 0; l < kWidth; ++l) {
      last[c * kWidth + l] = j + l < n ? x[c * rows + from + j + l] : xi[c];
    }
  }
  const Floats value = valueOf([&](std::size_t c) { return load(last + c * kWidth); });
  for (std::size_t l = 0; j + l < n; ++l) k[j + l] = value[l];
}

/// The same with point terms or many features, in blocks of rows whose squared distances stay in
/// L1 while each feature column adds to them, as columnByFeature does in double. Plain loops, which
/// the compiler vectorises: each operation is one IEEE float operation (multiply-adds explicit),
/// the same in the vector body and in the remainder, so a value depends on its row alone here too.
void columnInFloatByFeature(const float* x, std::size_t rows, std::size_t features, std::size_t i,
                            std::size_t from, std::size_t to, const GramKernel& kernel, double* k) {
  const std::size_t n = to - from;
  const std::size_t block = kernel.block == 0 ? features : kernel.block;
  const float halfGamma = static_cast<float>(0.5 * kernel.gamma);
  const float wholeWeight = static_cast<float>(kernel.wholeWeight);
  const float pointWeight = static_cast<float>(kernel.pointWeight);
  for (std::size_t begin = 0; begin < n; begin += kBlock) {
    const std::size_t size = n - begin < kBlock ? n - begin : kBlock;
    float whole[kBlock], points[kBlock], r2[kBlock];
    for (std::size_t j = 0; j < size; ++j) whole[j] = points[j] = 0;
    for (std::size_t g = 0; g < features; g += block) {
      if (block == 3) {
        addControlPointTerms(x, rows, g, i, from + begin, size, halfGamma, whole, points);
        continue;
      }
      for (std::size_t j = 0; j < size; ++j) r2[j] = 0;
      for (std::size_t c = g; c < g + block; ++c) {
        const float* values = x + c * rows + from + begin;
        const float xi = x[c * rows + i];
        for (std::size_t j = 0; j < size; ++j) {
          const float t = values[j] - xi;
          r2[j] = mulAdd(t, t, r2[j]);
        }
      }
      for (std::size_t j = 0; j < size; ++j) whole[j] += r2[j];
      if (kernel.block == 0) continue;
      for (std::size_t j = 0; j < size; ++j) {
        const float t = mulAdd(halfGamma, r2[j], 1.0f);
        points[j] += 1 / (t * t);
      }
    }
    double* out = k + begin;
    for (std::size_t j = 0; j < size; ++j) {
      const float t = mulAdd(halfGamma, whole[j], 1.0f);
      const float term = 1 / (t * t);
      out[j] = kernel.block == 0 ? term : mulAdd(pointWeight, points[j], wholeWeight * term);
    }
  }
}

/// A rational-quadratic Gram column in float: one term of few features a register of rows at a
/// time, point terms or many features a block of rows at a time. Measured at N 8000 (`BM_Train`,
/// pinned): a register of rows d 7 2.56 ms, d 9 3.13-3.20 ms against 3.13-3.14 and 3.80-3.84 by
/// blocks; point terms d 9 5.09-5.12 and d 12 6.56-6.62 ms against 4.67-4.75 and 6.00-6.09.
void columnInFloat(const float* x, std::size_t rows, std::size_t features, std::size_t i,
                   std::size_t from, std::size_t to, const GramKernel& kernel, double* k) {
  if (kernel.block == 0 && features <= kRowFeatures) {
    columnInFloatByRow(x, rows, features, i, from, to, kernel, k);
  } else {
    columnInFloatByFeature(x, rows, features, i, from, to, kernel, k);
  }
}

/// The kernel between a register of points (xj: one register per feature) and one point s, each
/// lane as kernelOfDifferences computes it. For addSums, which reuses xj over the whole support
/// set; columnByRow keeps its own loops, which load each feature where they use it: built on this
/// function, loading the features into xj first, Algorithm 1 took 1.3-1.6 times longer
/// (`BM_Train` N 8000, d 7 one term 2.44 -> 3.76 ms, d 12 point terms 7.59 -> 9.94 ms).
inline Doubles kernelOfRegister(const Doubles* xj, const double* s, std::size_t features,
                                const GramKernel& kernel) {
  const std::size_t block = kernel.block == 0 ? features : kernel.block;
  if (kernel.type != KernelType::RationalQuadratic) {  // lane by lane (an exponential each)
    Doubles value;
    for (std::size_t lane = 0; lane < kDoubles; ++lane) {
      value[lane] =
          kernelOfDifferences([&](std::size_t c) { return xj[c][lane] - s[c]; }, features, kernel);
    }
    return value;
  }
  const Doubles halfGammas = 0.5 * kernel.gamma - Doubles{};
  Doubles whole = {}, points = {};
  for (std::size_t g = 0; g < features; g += block) {
    Doubles r2 = {};
    for (std::size_t c = g; c < g + block; ++c) {
      const Doubles t = xj[c] - s[c];
      r2 = mulAdd(t, t, r2);
    }
    whole += r2;
    if (kernel.block != 0) points += termOf(r2, halfGammas);
  }
  if (kernel.block == 0) return termOf(whole, halfGammas);
  return (kernel.wholeWeight - Doubles{}) * termOf(whole, halfGammas) +
         (kernel.pointWeight - Doubles{}) * points;
}

/// A register of new rows at a time, their features loaded once and every support point read
/// from one contiguous row: one pass over the support set per register, no column stored and
/// read back (the Gram-column form took 1.1 ms for 2000 new points and 540 support points in
/// 12 features; see docs/performance.md).
void addSums(const double* support, const double* weights, std::size_t count, const double* x,
             std::size_t rows, std::size_t features, std::size_t from, std::size_t to,
             const GramKernel& kernel, double* f) {
  const std::size_t n = to - from;
  Doubles xj[kMaxGramFeatures];
  std::size_t j = 0;
  for (; j + kDoubles <= n; j += kDoubles) {
    for (std::size_t c = 0; c < features; ++c) xj[c] = load(x + c * rows + from + j);
    Doubles sum = load(f + j);
    for (std::size_t s = 0; s < count; ++s) {
      sum = mulAdd(weights[s] - Doubles{},
                   kernelOfRegister(xj, support + s * features, features, kernel), sum);
    }
    __builtin_memcpy(f + j, &sum, sizeof sum);
  }
  for (; j < n; ++j) {  // the last rows, one lane each
    for (std::size_t c = 0; c < features; ++c) xj[c] = x[c * rows + from + j] - Doubles{};
    double sum = f[j];
    for (std::size_t s = 0; s < count; ++s) {
      sum = mulAdd(weights[s], kernelOfRegister(xj, support + s * features, features, kernel)[0],
                   sum);
    }
    f[j] = sum;
  }
}

/// Two passes: F with its minimum margin, then the index of the minimum.
double addAndFindWorst(double* f, const double* y, std::size_t n, const double* k, double delta,
                       std::size_t* worst) {
  // F and the minimum in one pass, a register at a time (the compiler would not reorder a
  // floating-point minimum); lanes start from a margin of the pass, the new y_0 F_0.
  const Doubles deltas = delta - Doubles{};
  Doubles lowestLanes = y[0] * mulAdd(delta, k[0], f[0]) - Doubles{};
  std::size_t j = 0;
  for (; j + kDoubles <= n; j += kDoubles) {
    const Doubles updated = mulAdd(deltas, load(k + j), load(f + j));
    __builtin_memcpy(f + j, &updated, sizeof updated);
    const Doubles margin = load(y + j) * updated;
    lowestLanes = margin < lowestLanes ? margin : lowestLanes;
  }
  double lowest = lowestLanes[0];
  for (std::size_t l = 1; l < kDoubles; ++l)
    lowest = lowestLanes[l] < lowest ? lowestLanes[l] : lowest;
  for (; j < n; ++j) {
    f[j] = mulAdd(delta, k[j], f[j]);
    lowest = y[j] * f[j] < lowest ? y[j] * f[j] : lowest;
  }
  std::size_t at = 0;
  while (at + 1 < n && y[at] * f[at] != lowest) ++at;
  *worst = at;
  return lowest;
}

}  // namespace

namespace FASTRON_SIMD_NAMESPACE {
const GramPasses kGramPasses{&column, &columnInFloat, &addSums, &addAndFindWorst};
}

}  // namespace fastron::detail
