#include "fastron/core/kernel.h"

#include <string>

#include "fastron/core/error.h"

namespace fastron {

void validate(const Kernel& kernel) {
  if (!std::isfinite(kernel.gamma) || kernel.gamma <= 0) {
    throw InvalidArgument("kernel gamma must be a finite positive number, got " +
                          std::to_string(kernel.gamma));
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
