#pragma once
// Trajectory optimisation on the model (issue 53): Baxter's 7-joint arm among the paper's three
// random-walk boxes; each query's straight line collides. From that straight line, the CHOMP-style
// optimiser on the model's collision cost (optimizeVerified: verified with FCL, the model learning
// what verification finds) against RRT-Connect on FCL and Fastron's default plan, both simplified.

#include <cstdint>

#include "fastron/core/feature_map.h"
#include "fastron/experiments/progress.h"
#include "fastron/experiments/table.h"
#include "fastron/planning/planner.h"
#include "fastron/planning/trajectory_optimization.h"

namespace fastron::experiments {

struct TrajectoryExperimentOptions {
  std::size_t trials = 10;  ///< queries, each after the boxes moved (--quick: 3)
  std::uint64_t seed = 1;
  bool quick = false;
  FeatureKind features = FeatureKind::Kinematic;
  double timeLimit = 10, resolution = 0.03, modelResolution = 0, simplifyTime = 0.1;
  PathSimplification simplification = PathSimplification::Full;
  TrajectoryOptions optimizer;
  std::size_t rounds = 4;  ///< optimizeVerified's: times the model learns and optimises again
  /// The Fastron row's repairs try gradient repair first (VerifyRepairOptions::gradientRepair).
  bool gradientRepair = false;
};

struct TrajectoryResults {
  /// One row per (trial, method): method (Optimizer, FCL, Fastron), solved, time_ms, of which
  /// learn_ms, iterations and rounds (the optimiser), length (joint units), colliding (the final
  /// path under a separate FCL at a third of the resolution), the model's support, accuracy, tpr.
  Table results;
  /// The model's score along each trial's path before (the straight line) and after optimising:
  /// trial, path (before, after), s (the share of the path's length), score.
  Table scores;
};

TrajectoryResults runTrajectories(const TrajectoryExperimentOptions& options,
                                  const Progress& progress);
std::string trajectoryReport(const TrajectoryResults& results,
                             const TrajectoryExperimentOptions& options);

}  // namespace fastron::experiments
