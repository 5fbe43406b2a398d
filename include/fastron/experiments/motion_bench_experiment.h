#pragma once
// MoveIt benchmark problems (MotionBenchMaker's scene and request files) for the Panda.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fastron/experiments/plan_results.h"
#include "fastron/experiments/progress.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {

/// The method `fastron plan` uses by default, reported first: a model of the scene's obstacles
/// (self-collisions left to verification), planned on with planVerifiedLearning.
inline constexpr const char* kDefaultMethod = "Fastron";

struct MotionBenchOptions {
  /// A family: a folder of sceneNNNN.yaml / requestNNNN.yaml pairs; or a folder of families
  /// (sub-folders of such pairs), each reported on its own and all together.
  std::filesystem::path problems;
  std::string robot = "panda";                      ///< a shipped robot or a URDF file (loadRobot)
  std::vector<std::filesystem::path> packagePaths;  ///< where its package:// meshes are
  std::filesystem::path srdf;  ///< an SRDF whose disabled collisions apply (empty: none)
  /// FCL (the oracle, the planner's and the audit) also checks the robot against itself.
  bool selfCollision = false;
  /// FCL checks every state of a motion (CheckerOptions::proveMotionsFree off): the same answers,
  /// for comparing what the clearance proof saves.
  bool denseChecks = false;
  /// With selfCollision and a robot whose self pairs hold meshes: every FCL checker but the
  /// audit's reads the robot's self-pair tables (pipeline::selfPairTables, built once and kept in
  /// selfModelCache), the exact baseline's as every method's.
  bool selfPairTables = true;
  /// Planning queries per scene: the request, then K - 1 start/goal pairs drawn uniformly and
  /// free under FCL, all on the one model trained for the scene (a robot that stays in a scene
  /// amortises the training).
  std::size_t queriesPerScene = 1;
  /// With selfCollision: also plan on "Fastron split", a self-collision model learned once for
  /// the robot (joint space, empty scene) beside each scene's model of obstacles only, verified
  /// and repaired with FCL (self-collision included) like the rest.
  bool selfModel = false;
  /// Between a scene's queries, the paper's model ("Fastron (paper)") learns the exact answers of
  /// the last plan's verification and repair that it got wrong
  /// (ProxyCollisionDetector::learnObservations: the scene stands still, so no oracle call).
  bool learnFromVerification = false;
  /// The default method's repairs try gradient repair first (VerifyRepairOptions::gradientRepair).
  bool gradientRepair = false;
  std::size_t selfTrainingPoints = 20000;  ///< samples of the self-collision model
  /// Where the self-collision model and the self-pair tables are kept and found again
  /// (pipeline::SelfModelOptions; empty: pipeline::defaultCacheDirectory()).
  std::filesystem::path selfModelCache;
  std::uint64_t seed = 1;
  bool quick = false;
  /// Uniform samples of each scene's models before active learning (unset: those of
  /// pipeline::SceneModelOptions, 1000).
  std::optional<std::size_t> trainingPoints;
  /// Active-learning updates of each scene's models after them (unset:
  /// pipeline::SceneModelOptions', 0), and of the self-collision model (unset:
  /// pipeline::SelfModelOptions', as `fastron plan --self-model auto`, whose cached model it
  /// shares).
  std::optional<std::size_t> updates;
  /// Kernel width and conditional bias of each scene's models (unset: the features' defaults,
  /// defaultTrainParams); not of the robot's self-collision model.
  std::optional<double> gamma, beta;
  /// Fastron's input (task-space features by default; joints for the paper's model).
  FeatureKind features = FeatureKind::Kinematic;
  double timeLimit = 10;
  /// Longest tree edge of every method's RRT-Connect to begin with, joint units (0: OMPL's
  /// default; PlannerOptions::range).
  double range = 0;
  /// Iterations without a path before the range is halved (unset: PlannerOptions::rangeStage;
  /// 0: the range stays).
  std::optional<std::size_t> rangeStage;
  double resolution = 0.03;
  double modelResolution = 0;  ///< PlannerOptions::modelResolution (0: 3 x resolution)
  /// Seconds of OMPL path simplification per plan, for every checker alike (0: off, the paper).
  double simplifyTime = 0.1;
  /// How every checker's whole paths are simplified (repairs' bridges always take Shortcuts).
  PathSimplification simplification = PathSimplification::Full;
  /// Where the rows so far (results.csv's format) are written after each problem, so that an
  /// interrupted run leaves what it finished (empty: nowhere).
  std::filesystem::path resultsFile;
};

/// Each problem: the robot as the request plans it (robotForRequest: the request's SRDF group
/// actuated, other joints where the scene and the start state put them), Fastron trained on the
/// scene, then RRT-Connect with the default method (kDefaultMethod), the paper's "Fastron
/// (paper)" and "Hybrid (paper)" (verified and repaired) and FCL on each query. One row per
/// (family, problem, query, method); query 0 is the request. A goal that touches objects with the
/// hand only is a grasp: hand-object contacts are allowed (as MoveIt's touch links do), and `note`
/// says so. A problem that cannot be run (a file that cannot be read, a request the robot cannot
/// take) is recorded in PlanRows::skipped with its error, and the run goes on. Throws FileError
/// naming the folder when it holds no problems, or the robot's files.
PlanRows runMotionBench(const MotionBenchOptions& options, const Progress& progress);
std::string motionBenchReport(const PlanRows& results, const MotionBenchOptions& options);

}  // namespace fastron::experiments
