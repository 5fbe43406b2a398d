#pragma once
// Sentences the reports share: what a model learned on, how paths were simplified, where a
// robot's self-pair tables came from.

#include <string>
#include "fastron/core/feature_map.h"
#include "fastron/pipeline/self_pair_tables.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {

/// A sentence for reports saying what Fastron learned on.
std::string featureSentence(FeatureKind kind);
/// A sentence for reports saying whether and how long paths were simplified.
std::string simplificationSentence(double simplifyTime, PathSimplification simplification);
/// "4 self pairs of meshes tabulated, read from FILE" (or "built in 6.14 s and kept in FILE"):
/// where tables that pipeline::selfPairTables gave (not null) came from.
std::string selfPairTablesText(const pipeline::SelfPairTables& tables);

}  // namespace fastron::experiments
