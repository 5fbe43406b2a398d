#pragma once
// The paper's planning experiments: Baxter with moving boxes and four planners (Sec. IV-C,
// Figs. 13 and 14), the UR3 shelf (Sec. V-A), the surgical assistant (Sec. V-B), and MoveIt
// benchmark problems for the Panda. Fastron and GJK plans are verified and repaired with FCL;
// every final path is checked again with a separate FCL checker.

#include <filesystem>
#include <string>
#include <vector>

#include "fastron/core/dataset.h"
#include "fastron/core/model.h"
#include "fastron/core/uncertainty_band.h"
#include "fastron/experiments/common.h"
#include "fastron/planning/planner.h"

namespace fastron {

struct PlanningOptions {
  std::size_t trials = 10;  ///< obstacle positions, each with its own start and goal
  std::uint64_t seed = 1;
  bool quick = false;
  std::vector<std::string> cases{"4dof", "6dof", "7dof", "7dof-3boxes"};
  std::vector<PlannerType> planners = allPlannerTypes();
  double timeLimit = 10;     ///< seconds per planning query (and per repaired stretch)
  double resolution = 0.03;  ///< joint-space step of edge checks (rad)
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
  /// Fastron's input (task-space features by default; joints for the paper's model).
  FeatureKind features = FeatureKind::Kinematic;
};

/// One row per (case, trial, planner, method): solved, status, plan_s, verify_s, repair_s,
/// total_s, path_length, waypoints, stretches (replanned), fallback (the whole motion was planned
/// on FCL), exact_ends (the approximate checker wrongly thought an end collided: see
/// planVerified), collides_fcl (the final path checked by an independent FCL checker).
Table runPlanning(const PlanningOptions& options, const Progress& progress);
std::string planningReport(const Table& results, const PlanningOptions& options);

struct ShelfOptions {
  std::size_t trials = 10;  ///< start/goal pairs
  std::uint64_t seed = 1;
  bool quick = false;
  /// Fastron's input (task-space features by default; joints for the paper's model).
  FeatureKind features = FeatureKind::Kinematic;
  double timeLimit = 10;
  double resolution = 0.03;
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
};

/// UR3 from the lower to the higher shelf with RRT: one row per (trial, method), columns as
/// runPlanning's.
Table runShelf(const ShelfOptions& options, const Progress& progress);
std::string shelfReport(const Table& results, const ShelfOptions& options);

struct SurgicalOptions {
  std::size_t ticks = 200;  ///< simulation ticks; every method replans at each
  std::uint64_t seed = 1;
  bool quick = false;
  double timeLimit = 1;
  double resolution = 0.01;  ///< joint units (rad, and m for the insertion)
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
  double padding = 0.005;  ///< PSM3 padding of the model's oracle (paper: a padded PSM3)
  /// Fastron's input (task-space features by default; joints for the paper's model).
  FeatureKind features = FeatureKind::Kinematic;
};

/// PSM3 replans an RRT every tick between home and a target among PSM1 and PSM2 moving on
/// circles, with the model updated in the background: one row per (tick, method), columns as
/// runPlanning's plus the model's support count.
Table runSurgical(const SurgicalOptions& options, const Progress& progress);
std::string surgicalReport(const Table& results, const SurgicalOptions& options);

struct MotionBenchOptions {
  std::filesystem::path problems;  ///< folder of sceneNNNN.yaml / requestNNNN.yaml pairs
  std::string robot = "panda";     ///< a shipped robot or a URDF file (loadRobot)
  std::vector<std::filesystem::path> packagePaths;  ///< where its package:// meshes are
  std::filesystem::path srdf;  ///< an SRDF whose disabled collisions apply (empty: none)
  bool selfCollision =
      false;  ///< FCL (the oracle, the planner's and the audit) checks self-collision
  std::uint64_t seed = 1;
  bool quick = false;
  std::size_t trainingPoints = 5000;  ///< initial samples of each scene's model
  std::size_t updates = 3;            ///< active-learning updates after them
  /// Fastron's input (task-space features by default; joints for the paper's model).
  FeatureKind features = FeatureKind::Kinematic;
  double timeLimit = 10;
  double resolution = 0.03;
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
};

/// Each problem: Fastron trained on the scene, RRT-Connect with Fastron (verified and repaired)
/// and with FCL. One row per (problem, method). A goal that touches one object with the hand only
/// is a grasp: hand-object contacts are allowed (as MoveIt's touch links do), and `note` says so.
Table runMotionBench(const MotionBenchOptions& options, const Progress& progress);
std::string motionBenchReport(const Table& results, const MotionBenchOptions& options);

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
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
  /// Feed the exact answers of verification and repair that the model got wrong to its next
  /// update.
  bool learnFromVerification = true;
  /// What the band of the Hybrid method (Fastron with FCL inside the band) is calibrated to.
  BandTargets band{};
};

/// `fastron demo`: the paper in one run.
struct DemoResults {
  /// One row per (tick, method): runPlanning's plan columns plus support, accuracy, tpr, tnr
  /// (the current model against FCL) and updates (background model updates so far).
  Table ticks;
  std::shared_ptr<const Model> model;  ///< the last model
  Dataset test;                        ///< the last tick's test configurations, FCL labels
  double fastronQuerySeconds = 0, gjkQuerySeconds = 0, fclQuerySeconds = 0;
  std::size_t updates = 0;       ///< background updates during the run
  double meanUpdateSeconds = 0;  ///< labelling + training, per update
  double elapsedSeconds = 0;     ///< of the planning loop
};

/// Baxter's 7-joint arm among three moving boxes: the model updates on a background thread from
/// FCL labels while, at every tick, the boxes move and RRT-Connect plans a fresh query with
/// Fastron (verified and repaired with FCL), GJK (verified and repaired) and FCL.
DemoResults runDemo(const DemoOptions& options, const Progress& progress);
std::string demoReport(const DemoResults& results, const DemoOptions& options);

}  // namespace fastron
