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

struct Kernel {
  KernelType type = KernelType::RationalQuadratic;
  double gamma = 10;  ///< width parameter, > 0; larger is narrower

  /// k as a function of the squared distance r2 = |x - x'|^2. k(x, x) = 1 for both kernels.
  template <class T>
  T operator()(T r2) const {
    if (type == KernelType::RationalQuadratic) {
      const T t = T(1) + T(0.5 * gamma) * r2;
      return T(1) / (t * t);
    }
    return std::exp(T(-gamma) * r2);
  }
};

/// Throws InvalidArgument unless gamma is finite and positive.
void validate(const Kernel& kernel);

/// "rq" or "gaussian".
std::string_view toString(KernelType type);

/// Parses "rq" / "rational-quadratic" / "gaussian"; throws InvalidArgument naming the value.
KernelType parseKernelType(std::string_view name);

}  // namespace fastron
