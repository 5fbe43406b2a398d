#pragma once
// Kernel functions of the Fastron model (paper, Sec. II-B).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

enum class KernelType : std::uint8_t {
  /// k(x,x') = (1 + gamma/2 |x-x'|^2)^-2: the rational-quadratic kernel with p = 2, the paper's
  /// cheap approximation of the Gaussian (no exponential).
  RationalQuadratic = 0,
  /// k(x,x') = exp(-gamma |x-x'|^2).
  Gaussian = 1,
};

/// The kernel widths accepted: queries compute in float, where a gamma outside this range would
/// be 0 or infinite.
inline constexpr double kMinKernelGamma = 1e-30, kMaxKernelGamma = 1e30;

/// The kernels' one formula, k as a function of the squared distance r2 = |x - x'|^2, for a
/// scalar (training, double queries) or an Eigen array of them (the float query path). k(x, x) = 1
/// for both kernels.
template <KernelType type, class R, class Scalar>
R kernelOfSquaredDistance(const R& r2, Scalar gamma) {
  if constexpr (type == KernelType::RationalQuadratic) {
    const R t = Scalar(1) + (Scalar(0.5) * gamma) * r2;
    return Scalar(1) / (t * t);
  } else {
    using std::exp;  // Eigen's own exp for arrays, found by argument-dependent lookup
    return exp(-gamma * r2);
  }
}

/// dk/dr2 of kernelOfSquaredDistance: -gamma t^-3 for the rational quadratic (t = 1 + gamma/2
/// r2), -gamma exp(-gamma r2) for the Gaussian.
template <KernelType type, class Scalar>
Scalar kernelDerivativeOfSquaredDistance(Scalar r2, Scalar gamma) {
  if constexpr (type == KernelType::RationalQuadratic) {
    const Scalar t = Scalar(1) + (Scalar(0.5) * gamma) * r2;
    return -gamma / (t * t * t);
  } else {
    return -gamma * std::exp(-gamma * r2);
  }
}

struct Kernel {
  KernelType type = KernelType::RationalQuadratic;
  double gamma = 10;  ///< width parameter, > 0; larger is narrower
  /// Features per point term. 0: one term, k(x, x') = k(|x - x'|^2) over the whole feature
  /// vector (the paper's kernel). b > 0: the vector is m = d / b blocks of b features (b = 3: the
  /// position of each control point), and
  ///   k(x, x') = s k(|x - x'|^2) + (1 - s) / m sum_g k(|x_g - x'_g|^2),   s = wholeShare,
  /// a term per point beside the term of the whole vector. A robot collides where any of its
  /// links does, and a sum over points models such a union far better than one kernel of all
  /// positions; the whole term keeps what only the points together say (a hand's orientation).
  /// docs/algorithms.md, "Kernel terms per control point". Always k(x, x) = 1.
  std::uint32_t block = 0;
  /// With block > 0: the share s of the whole vector's term, in [0, 1].
  double wholeShare = 0;

  /// One term as a function of its squared distance r2 (kernelOfSquaredDistance).
  template <class T>
  T operator()(T r2) const {
    return type == KernelType::RationalQuadratic
               ? kernelOfSquaredDistance<KernelType::RationalQuadratic>(r2, T(gamma))
               : kernelOfSquaredDistance<KernelType::Gaussian>(r2, T(gamma));
  }

  /// dk/dr2 of one term at squared distance r2.
  double derivative(double r2) const {
    return type == KernelType::RationalQuadratic
               ? kernelDerivativeOfSquaredDistance<KernelType::RationalQuadratic>(r2, gamma)
               : kernelDerivativeOfSquaredDistance<KernelType::Gaussian>(r2, gamma);
  }
  /// Point terms for `dim` features: 0 for the one-term kernel.
  std::size_t pointTerms(std::size_t dim) const { return block == 0 ? 0 : dim / block; }
  /// The weights of the whole term and of each point term's sum: (1, 0) for the one-term kernel,
  /// else (s, (1 - s) / m).
  double wholeWeight() const { return block == 0 ? 1.0 : wholeShare; }
  double pointWeight(std::size_t dim) const {
    return block == 0 ? 0.0 : (1.0 - wholeShare) / static_cast<double>(pointTerms(dim));
  }

  /// k(a, b) of two vectors of `dim` features read feature by feature, a(c) and b(c) (a row of a
  /// matrix stored column by column reads in place). With point terms: r2 of each block in order,
  /// its term, the whole r2 as the sum of the blocks' r2 in order, then wholeWeight k(whole) +
  /// pointWeight (sum of the point terms): every path of Algorithm 1 and of the queries computes
  /// it in this order.
  template <class T, class A, class B>
  T between(const A& a, const B& b, std::size_t dim) const {
    const auto squared = [&](std::size_t c) { return (a(c) - b(c)) * (a(c) - b(c)); };
    if (block == 0) {
      T r2 = 0;
      for (std::size_t c = 0; c < dim; ++c) r2 += squared(c);
      return (*this)(r2);
    }
    T whole = 0, points = 0;
    for (std::size_t g = 0; g < dim; g += block) {
      T r2 = 0;
      for (std::size_t c = g; c < g + block; ++c) r2 += squared(c);
      whole += r2;
      points += (*this)(r2);
    }
    return T(wholeWeight()) * (*this)(whole) + T(pointWeight(dim)) * points;
  }
};

/// Throws InvalidArgument unless gamma is finite and positive.
void validate(const Kernel& kernel);
/// The same, the block must divide `featureDim` (a model's or a training set's features) and
/// the whole term's share be in [0, 1].
void validate(const Kernel& kernel, std::size_t featureDim);

/// "one term", "a term per 3 features (4) and the whole vector's, share 0.2" or "a term per 3
/// features (4), no whole-vector term": for reports.
std::string describeTerms(const Kernel& kernel, std::size_t featureDim);

/// "rq" or "gaussian".
std::string_view toString(KernelType type);

/// Parses "rq" / "rational-quadratic" / "gaussian"; throws InvalidArgument naming the value.
KernelType parseKernelType(std::string_view name);

}  // namespace fastron
