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

void validate(const Kernel& kernel, std::size_t featureDim) {
  validate(kernel);
  if (kernel.block != 0 && featureDim % kernel.block != 0) {
    throw InvalidArgument("kernel block " + std::to_string(kernel.block) +
                          " does not divide the feature dimension " + std::to_string(featureDim));
  }
  if (!(kernel.wholeShare >= 0 && kernel.wholeShare <= 1)) {
    throw InvalidArgument("the kernel's whole-vector share must be between 0 and 1, got " +
                          std::to_string(kernel.wholeShare));
  }
}

std::string describeTerms(const Kernel& kernel, std::size_t featureDim) {
  if (kernel.block == 0) return "one term";
  if (kernel.wholeShare == 0) {
    return "a term per " + std::to_string(kernel.block) + " features (" +
           std::to_string(kernel.pointTerms(featureDim)) + "), no whole-vector term";
  }
  char share[32];
  std::snprintf(share, sizeof share, "%g", kernel.wholeShare);
  return "a term per " + std::to_string(kernel.block) + " features (" +
         std::to_string(kernel.pointTerms(featureDim)) + ") and the whole vector's, share " + share;
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
