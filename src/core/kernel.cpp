#include "fastron/core/kernel.h"

#include <cstdio>
#include <string>

#include "fastron/core/error.h"

namespace fastron {

void validate(const Kernel& kernel) {
  // Queries compute in float: a gamma beyond its range would be infinite there.
  if (!(kernel.gamma >= kMinKernelGamma && kernel.gamma <= kMaxKernelGamma)) {
    char value[32];
    std::snprintf(value, sizeof value, "%g", kernel.gamma);
    throw InvalidArgument(std::string("kernel gamma must be between 1e-30 and 1e30, got ") + value);
  }
  if (kernel.type != KernelType::RationalQuadratic && kernel.type != KernelType::Gaussian) {
    throw InvalidArgument("unknown kernel type " + std::to_string(static_cast<int>(kernel.type)));
  }
}

std::string_view toString(KernelType type) {
  return type == KernelType::Gaussian ? "gaussian" : "rq";
}

KernelType parseKernelType(std::string_view name) {
  if (name == "rq" || name == "rational-quadratic") return KernelType::RationalQuadratic;
  if (name == "gaussian") return KernelType::Gaussian;
  throw InvalidArgument("unknown kernel '" + std::string(name) + "' (expected 'rq' or 'gaussian')");
}

}  // namespace fastron
