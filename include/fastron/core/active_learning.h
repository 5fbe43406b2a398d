#pragma once
// Algorithm 2 of the paper: active learning for the next model update.

#include <cstddef>

#include "fastron/core/model.h"
#include "fastron/core/types.h"

namespace fastron {

struct ActiveLearningParams {
  std::size_t maxSamples = 500;            ///< A_max: configurations returned
  std::size_t samplesPerSupportPoint = 5;  ///< kappa: exploitation samples per support point
  /// sigma^2 of the exploitation Gaussians, in input space; 0 means the paper's 1 / (2 gamma).
  double variance = 0;
};

/// Throws InvalidArgument naming the field that is out of range.
void validate(const ActiveLearningParams& params);

/// Returns A_max new, unlabelled configurations (joint values, one per row).
/// Exploitation: round k = 1..kappa draws one sample from N(s, sigma^2 I) around each support
/// point s, clamped to [-1, 1]^d, until A_max samples exist; when kappa |S| > A_max the support
/// points are visited in a random order, so the samples are not biased toward low indices.
/// Exploration: uniform samples in [-1, 1]^d fill the rest.
Configurations activeLearning(const Model& model, const ActiveLearningParams& params, Rng& rng);

/// n configurations drawn uniformly within the joint limits (the initial training set).
Configurations uniformConfigurations(const JointLimits& limits, std::size_t n, Rng& rng);

}  // namespace fastron
