#pragma once
// Sentences the reports share: what a model learned on, how paths were simplified.

#include <string>
#include "fastron/core/feature_map.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {

/// A sentence for reports saying what Fastron learned on.
std::string featureSentence(FeatureKind kind);
/// A sentence for reports saying whether and how long paths were simplified.
std::string simplificationSentence(double simplifyTime, PathSimplification simplification);

}  // namespace fastron::experiments
