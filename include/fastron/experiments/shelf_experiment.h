#pragma once
// The UR3 reaching from the lower to the higher shelf with RRT (paper, Sec. V-A).

#include <string>
#include <vector>

#include "fastron/experiments/plan_results.h"
#include "fastron/experiments/progress.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {

struct ShelfOptions {
  std::size_t trials = 10;  ///< start/goal pairs
  std::uint64_t seed = 1;
  bool quick = false;
  /// Fastron's input (task-space features by default; joints for the paper's model).
  FeatureKind features = FeatureKind::Kinematic;
  double timeLimit = 10;
  double resolution = 0.03;
  double modelResolution = 0;  ///< PlannerOptions::modelResolution (0: 3 x resolution)
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
  /// How every checker's whole paths are simplified (repairs' bridges always take Shortcuts).
  PathSimplification simplification = PathSimplification::Full;
};

/// UR3 from the lower to the higher shelf with RRT: one row per (trial, method), columns as
/// runPlanning's.
PlanRows runShelf(const ShelfOptions& options, const Progress& progress);
std::string shelfReport(const PlanRows& results, const ShelfOptions& options);

}  // namespace fastron::experiments
