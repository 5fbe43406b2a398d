#pragma once
// MoveIt benchmark problems (MotionBenchMaker's scene and request files) for the Panda.

#include <filesystem>
#include <string>
#include <vector>

#include "fastron/experiments/common.h"
#include "fastron/planning/planner.h"

namespace fastron {

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

}  // namespace fastron
