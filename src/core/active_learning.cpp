#include "fastron/core/active_learning.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "fastron/core/error.h"

namespace fastron {

void validate(const ActiveLearningParams& params) {
  if (!std::isfinite(params.variance) || params.variance < 0) {
    throw InvalidArgument(
        "active learning variance must be finite and >= 0 (0 = 1/(2 gamma)), got " +
        std::to_string(params.variance));
  }
  if (!(params.exploitationShare >= 0 && params.exploitationShare <= 1)) {
    throw InvalidArgument("active learning exploitation share must be in [0, 1], got " +
                          std::to_string(params.exploitationShare));
  }
}

double defaultVariance(const Model& model) {
  if (model.features().kind() == FeatureKind::JointScaling)
    return 1.0 / (2.0 * model.kernel().gamma);
  return kTaskSpaceVariance;
}

std::size_t defaultSamplesPerSupportPoint(const Model& model) {
  return model.features().kind() == FeatureKind::JointScaling ? 5
                                                              : kTaskSpaceSamplesPerSupportPoint;
}

Configurations activeLearning(const Model& model, const ActiveLearningParams& params, Rng& rng) {
  validate(params);
  const JointLimits& limits = model.limits();
  const auto d = static_cast<Eigen::Index>(model.dim());
  const auto maxSamples = static_cast<Eigen::Index>(params.maxSamples);
  // Samples are drawn in scaled joint space [-1, 1]^d whatever the features: Algorithm 2 needs
  // configurations, and task-space features have no inverse.
  const Configurations support = limits.toInput(model.supportConfigurations());
  const double variance = params.variance > 0 ? params.variance : defaultVariance(model);

  Configurations samples(maxSamples, d);  // scaled joint space
  Eigen::Index count = 0;

  // Exploitation: up to kappa Gaussian samples around each support point (Alg. 2, line 5), at
  // most exploitationShare of them all.
  const auto exploitation = static_cast<Eigen::Index>(
      std::floor(params.exploitationShare * static_cast<double>(params.maxSamples)));
  std::vector<Eigen::Index> order(static_cast<std::size_t>(support.rows()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  const std::size_t kappa = params.samplesPerSupportPoint > 0
                                ? params.samplesPerSupportPoint
                                : defaultSamplesPerSupportPoint(model);
  if (kappa * order.size() > static_cast<std::size_t>(exploitation)) {
    std::shuffle(order.begin(), order.end(), rng);
  }
  std::normal_distribution<double> gauss(0.0, std::sqrt(variance));
  for (std::size_t k = 0; k < kappa && count < exploitation; ++k) {
    for (const Eigen::Index s : order) {
      if (count == exploitation) break;
      for (Eigen::Index j = 0; j < d; ++j) {
        samples(count, j) = std::clamp(support(s, j) + gauss(rng), -1.0, 1.0);
      }
      ++count;
    }
  }

  // Exploration: uniform samples in [-1, 1]^d fill the rest (Alg. 2, line 8).
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (; count < maxSamples; ++count) {
    for (Eigen::Index j = 0; j < d; ++j) samples(count, j) = uniform(rng);
  }
  return limits.toJoint(samples);
}

Configurations uniformConfigurations(const JointLimits& limits, std::size_t n, Rng& rng) {
  const auto d = static_cast<Eigen::Index>(limits.dim());
  Configurations q(static_cast<Eigen::Index>(n), d);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    for (Eigen::Index j = 0; j < d; ++j) {
      std::uniform_real_distribution<double> uniform(limits.lower()[j], limits.upper()[j]);
      q(i, j) = uniform(rng);
    }
  }
  return q;
}

}  // namespace fastron
