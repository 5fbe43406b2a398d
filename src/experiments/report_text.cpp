#include "fastron/experiments/report_text.h"

#include <cstdio>
#include <sstream>
#include "fastron/experiments/statistics.h"

namespace fastron::experiments {

std::string featureSentence(FeatureKind kind) {
  return kind == FeatureKind::Kinematic
             ? "Fastron learns on task-space features: the world positions of the robot's "
               "automatic control points (docs/algorithms.md)."
             : "Fastron learns on joint values scaled to [-1, 1] (the paper's input).";
}

std::string simplificationSentence(double simplifyTime, PathSimplification simplification) {
  if (simplifyTime <= 0) return "Paths are not simplified (the paper's setting).";
  std::ostringstream s;
  s << "Every method's path is simplified with OMPL's PathSimplifier for up to " << simplifyTime
    << " s, on the checker that planned it (FCL pays for its simplification in exact checks; "
       "Fastron's is checked on the model and then verified), "
    << (simplification == PathSimplification::Full
            ? "as MoveIt does by default."
            : "by shortcutting and vertex reduction alone (no B-spline smoothing).");
  return s.str();
}

std::string selfPairTablesText(const pipeline::SelfPairTables& tables) {
  std::string text = std::to_string(tables.tables->size()) + " self pairs of meshes tabulated, ";
  if (tables.fromCache) return text + "read from " + tables.file.string();
  text += "built in " + durationText(tables.buildSeconds);
  return tables.file.empty() ? text : text + " and kept in " + tables.file.string();
}

}  // namespace fastron::experiments
