#pragma once
// LIBSVM's C-SVC (Debian libsvm-dev): the tool most users would try first. LIBSVM has no
// rational-quadratic kernel, so it uses its RBF kernel exp(-gamma |x - x'|^2) with the same gamma.

#include "fastron/baselines/classifier.h"
#include "fastron/core/export.h"
#include "fastron/core/joint_limits.h"

namespace FASTRON_API fastron {

class LibsvmClassifier final : public Classifier {
 public:
  LibsvmClassifier(JointLimits limits, double gamma, double C, double tolerance = 1e-3);
  std::string name() const override { return "LIBSVM"; }
  void train(const Configurations& q, std::span<const std::int8_t> labels) override;
  double score(const double* q) const override { return model_.score(q); }
  std::size_t supportCount() const override { return model_.supportCount(); }
  const KernelExpansion& expansion() const { return model_; }

 private:
  JointLimits limits_;
  double gamma_, C_, tolerance_;
  KernelExpansion model_;
};

}  // namespace fastron
