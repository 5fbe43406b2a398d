#pragma once
// `fastron demo`: the paper in one run (Baxter's 7-joint arm among three moving boxes).

#include <memory>
#include <optional>

#include <string>
#include <vector>
#include "fastron/core/dataset.h"
#include "fastron/core/model.h"
#include "fastron/core/uncertainty_band.h"

#include "fastron/experiments/plan_results.h"
#include "fastron/experiments/progress.h"
#include "fastron/geometry/control_points.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {

struct DemoOptions {
  std::size_t ticks = 150;   ///< obstacle moves, each followed by a fresh planning query
  double tickSeconds = 0.1;  ///< a tick lasts at least this long (sensing at 10 Hz)
  std::uint64_t seed = 1;
  std::size_t initialPoints = 3000;
  std::size_t testPoints = 1000;  ///< fresh configurations scoring the model at each tick
  /// Fastron's input (task-space features by default; joints for the paper's model).
  FeatureKind features = FeatureKind::Kinematic;
  double timeLimit = 5;
  double resolution = 0.03;
  double modelResolution = 0;  ///< PlannerOptions::modelResolution (0: 3 x resolution)
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
  /// How every checker's whole paths are simplified (repairs' bridges always take Shortcuts).
  PathSimplification simplification = PathSimplification::Full;
  /// Feed the exact answers of verification and repair that the model got wrong to its next
  /// update.
  bool learnFromVerification = true;
  /// What the band of the Hybrid method (Fastron with FCL inside the band) is calibrated to.
  BandTargets band{};
  /// Task-space features: the whole vector's share of the kernel (Kernel::wholeShare) and its
  /// width; unset: the defaults (0.5, 40). A share of 0 leaves point terms alone, and every
  /// model is published with its point field (ProxyParams::pointField).
  std::optional<double> wholeShare, gamma;
  /// How those point fields answer what their grids leave undecided (ProxyParams::fieldAnswers).
  FieldAnswers fieldAnswers = FieldAnswers::Exact;
  /// The conditional bias (TrainParams::beta); unset: the case's.
  std::optional<double> beta;
  /// Task-space features: how the robot's control points are chosen (defaultControlPoints).
  ControlPointOptions controlPoints{};
};

/// `fastron demo`: the paper in one run.
struct DemoResults {
  /// One row per (tick, method), with the figures support, accuracy, tpr, tnr (the current
  /// model against FCL) and updates (background model updates so far).
  PlanRows ticks;
  /// The model the last tick planned on and was scored with: `test` gives its last accuracy
  /// again (a newer one may have been published after the tick, on the same scene).
  std::shared_ptr<const Model> model;
  Dataset test;  ///< the last tick's test configurations, FCL labels
  double fastronQuerySeconds = 0, gjkQuerySeconds = 0, fclQuerySeconds = 0;
  std::size_t updates = 0;  ///< background updates during the run
  /// Ticks with no query: the boxes left no free start or goal in 20000 samples on a side.
  std::size_t blockedTicks = 0;
  double meanUpdateSeconds = 0;  ///< labelling + training, per update
  double elapsedSeconds = 0;     ///< of the planning loop
};

/// Baxter's 7-joint arm among three moving boxes: the model updates on a background thread from
/// FCL labels while, at every tick, the boxes move and RRT-Connect plans a fresh query with
/// Fastron (verified and repaired with FCL), GJK (verified and repaired) and FCL.
DemoResults runDemo(const DemoOptions& options, const Progress& progress);
std::string demoReport(const DemoResults& results, const DemoOptions& options);

}  // namespace fastron::experiments
