#pragma once
// The surgical assistant: PSM3 replanning among two moving PSMs (paper, Sec. V-B).

#include <string>
#include <vector>

#include "fastron/experiments/plan_results.h"
#include "fastron/experiments/progress.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {

struct SurgicalOptions {
  std::size_t ticks = 200;  ///< simulation ticks; every method replans at each
  std::uint64_t seed = 1;
  bool quick = false;
  double timeLimit = 1;
  double resolution = 0.01;    ///< joint units (rad, and m for the insertion)
  double modelResolution = 0;  ///< PlannerOptions::modelResolution (0: 3 x resolution)
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
  /// How every checker's whole paths are simplified (repairs' bridges always take Shortcuts).
  PathSimplification simplification = PathSimplification::Full;
  double padding = 0.005;  ///< PSM3 padding of the model's oracle (paper: a padded PSM3)
  /// Fastron's input (task-space features by default; joints for the paper's model).
  FeatureKind features = FeatureKind::Kinematic;
};

/// PSM3 replans an RRT every tick between home and a target among PSM1 and PSM2 moving on
/// circles, with the model updated in the background: one row per (tick, method), columns as
/// runPlanning's plus the model's support count.
PlanRows runSurgical(const SurgicalOptions& options, const Progress& progress);
std::string surgicalReport(const PlanRows& results, const SurgicalOptions& options);

}  // namespace fastron::experiments
