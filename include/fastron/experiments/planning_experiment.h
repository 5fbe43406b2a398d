#pragma once
// The paper's planning experiment (Sec. IV-C, Figs. 13 and 14): Baxter with moving boxes and four
// planners. Fastron, Hybrid and GJK plans are verified and repaired with FCL; every final path is
// checked again with a separate FCL checker.

#include <string>
#include <vector>

#include "fastron/experiments/plan_results.h"
#include "fastron/experiments/progress.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {

struct PlanningOptions {
  std::size_t trials = 10;  ///< obstacle positions, each with its own start and goal
  std::uint64_t seed = 1;
  bool quick = false;
  std::vector<std::string> cases{"4dof", "6dof", "7dof", "7dof-3boxes"};
  std::vector<PlannerType> planners = allPlannerTypes();
  double timeLimit = 10;       ///< seconds per planning query (and per repaired stretch)
  double resolution = 0.03;    ///< joint-space step of edge checks (rad)
  double modelResolution = 0;  ///< PlannerOptions::modelResolution (0: 3 x resolution)
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
  /// How every checker's whole paths are simplified (repairs' bridges always take Shortcuts).
  PathSimplification simplification = PathSimplification::Full;
  /// Fastron's input (task-space features by default; joints for the paper's model).
  FeatureKind features = FeatureKind::Kinematic;
};

/// One row per (case, trial, planner, method), with the model's support, accuracy and tpr
/// (against FCL on fresh uniform configurations) as figures.
PlanRows runPlanning(const PlanningOptions& options, const Progress& progress);
std::string planningReport(const PlanRows& results, const PlanningOptions& options);

}  // namespace fastron::experiments
