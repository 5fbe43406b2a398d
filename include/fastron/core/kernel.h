#pragma once
// Kernel functions of the Fastron model (paper, Sec. II-B).

#include <cmath>
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

struct Kernel {
  KernelType type = KernelType::RationalQuadratic;
  double gamma = 10;  ///< width parameter, > 0; larger is narrower

  /// k as a function of the squared distance r2 (kernelOfSquaredDistance).
  template <class T>
  T operator()(T r2) const {
    return type == KernelType::RationalQuadratic
               ? kernelOfSquaredDistance<KernelType::RationalQuadratic>(r2, T(gamma))
               : kernelOfSquaredDistance<KernelType::Gaussian>(r2, T(gamma));
  }
};

/// Throws InvalidArgument unless gamma is finite and positive.
void validate(const Kernel& kernel);

/// "rq" or "gaussian".
std::string_view toString(KernelType type);

/// Parses "rq" / "rational-quadratic" / "gaussian"; throws InvalidArgument naming the value.
KernelType parseKernelType(std::string_view name);

}  // namespace fastron
