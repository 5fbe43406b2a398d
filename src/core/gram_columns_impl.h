// The passes of Algorithm 1 over the training points, written once and compiled once per SimdPath:
// each gram_columns_*.cpp defines FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH and includes this
// file with its own -march flags. Plain loops the compiler vectorises, in functions of internal
// linkage calling nothing from outside but the C library's exp (see simd_lanes.h for why).
//
// No include guard: included once per translation unit.

#if !defined(FASTRON_SIMD_NAMESPACE) || !defined(FASTRON_SIMD_WIDTH)
#error "define FASTRON_SIMD_NAMESPACE and FASTRON_SIMD_WIDTH before including gram_columns_impl.h"
#endif

#include <cstddef>

#include "gram_columns.h"

namespace fastron::detail {
namespace {

/// a * b + c, fused where the instruction set can (these files compile with -ffp-contract=off;
/// without FMA instructions, __builtin_fma would be a call to the C library).
inline double mulAdd(double a, double b, double c) {
#ifdef __FMA__
  return __builtin_fma(a, b, c);
#else
  return a * b + c;
#endif
}

// Doubles per register.
constexpr std::size_t kDoubles = FASTRON_SIMD_WIDTH / 2;
using Doubles = double __attribute__((vector_size(FASTRON_SIMD_WIDTH * 4)));

inline Doubles loadDoubles(const double* p) {
  Doubles v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

// Rows go in blocks whose squared distances stay in L1 while every feature column adds to them:
// with 27 features, summing into the whole column instead moved it through the cache 27 times.
constexpr std::size_t kBlock = 256;

void column(const double* x, std::size_t rows, std::size_t features, std::size_t i,
            std::size_t from, KernelType type, double gamma, double* k) {
  const std::size_t n = rows - from;
  for (std::size_t begin = 0; begin < n; begin += kBlock) {
    const std::size_t size = n - begin < kBlock ? n - begin : kBlock;
    double* r2 = k + begin;
    for (std::size_t j = 0; j < size; ++j) r2[j] = 0;
    for (std::size_t c = 0; c < features; ++c) {
      const double* values = x + c * rows + from + begin;
      const double xi = x[c * rows + i];
      for (std::size_t j = 0; j < size; ++j) {
        const double t = values[j] - xi;
        r2[j] = mulAdd(t, t, r2[j]);
      }
    }
    // One loop per kernel type (the formulas of kernelOfSquaredDistance): a branch inside would
    // stop the loop vectorising.
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
}

/// Three passes that each vectorise (a fused loop does not: the compiler keeps a floating-point
/// minimum in order), over data that stays in cache.
double addAndFindWorst(double* f, const double* y, std::size_t n, const double* k, double delta,
                       std::size_t* worst) {
  for (std::size_t j = 0; j < n; ++j) f[j] = mulAdd(delta, k[j], f[j]);
  // The minimum a register at a time (the compiler would not reorder a floating-point minimum).
  Doubles lowestLanes = {};
  lowestLanes += y[0] * f[0];
  std::size_t j = 0;
  for (; j + kDoubles <= n; j += kDoubles) {
    const Doubles margin = loadDoubles(y + j) * loadDoubles(f + j);
    lowestLanes = margin < lowestLanes ? margin : lowestLanes;
  }
  double lowest = lowestLanes[0];
  for (std::size_t l = 1; l < kDoubles; ++l)
    lowest = lowestLanes[l] < lowest ? lowestLanes[l] : lowest;
  for (; j < n; ++j) lowest = y[j] * f[j] < lowest ? y[j] * f[j] : lowest;
  std::size_t at = 0;
  while (at + 1 < n && y[at] * f[at] != lowest) ++at;
  *worst = at;
  return lowest;
}

}  // namespace

namespace FASTRON_SIMD_NAMESPACE {
const GramPasses kGramPasses{&column, &addAndFindWorst};
}

}  // namespace fastron::detail
