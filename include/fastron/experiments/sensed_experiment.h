#pragma once
// The changing-environment experiment as a robot would live it: Baxter's arm among moving boxes
// over a table that it sees only through a simulated depth camera. Every frame the cloud is
// ingested (down-sampled, handed to the exact checker) and the model updates from the checker on
// the cloud; plans on the model are verified on the cloud and audited against the true boxes.

#include <string>

#include "fastron/core/feature_map.h"
#include "fastron/experiments/plan_results.h"
#include "fastron/experiments/progress.h"
#include "fastron/experiments/table.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {

struct SensedOptions {
  std::size_t trials = 3;
  std::size_t frames = 60;     ///< camera frames (model updates) per trial
  std::size_t planEvery = 10;  ///< a planning query every this many frames
  std::uint64_t seed = 1;
  bool quick = false;
  FeatureKind features = FeatureKind::Kinematic;
  double radius = 0.01;  ///< of each point's ball; the cloud is down-sampled at it
  /// The model's kernel width and conditional bias; 0 keeps those of the models of a scene's
  /// obstacles (sceneTrainParams: for task-space features gamma 60, beta 40).
  double gamma = 0, beta = 0;
  /// A_max, the active-learning samples per update; 0 keeps the features' default.
  std::size_t activeSamples = 0;
  double depthNoise = 0.002;
  int width = 424, height = 240;  ///< the camera's pixels (a RealSense D435's depth stream)
  double timeLimit = 1, resolution = 0.03, modelResolution = 0, simplifyTime = 0.1;
  PathSimplification simplification = PathSimplification::Full;
};

struct SensedResults {
  /// One row per (trial, frame): raw_points, kept_points (after down-sampling), reach_points
  /// (within the arm's reach), camera_s (rendering, not the robot's cost), ingest_s
  /// (down-sampling and the checker's grid), update_s (labelling and training; of which label_s
  /// and train_s), updates_per_s
  /// (1 / (ingest_s + update_s)), the model's accuracy and TPR against FCL on the cloud
  /// (accuracy_cloud, tpr_cloud) and on the true boxes (accuracy_truth, tpr_truth), cloud_truth
  /// (the share of configurations on which FCL on the cloud and on the boxes agree), support,
  /// query_s (the model) and fcl_query_s (FCL on the cloud).
  Table frames;
  /// Fastron (verified and repaired on the cloud) and FCL on the cloud, a query every planEvery
  /// frames; collides_fcl audits the path against the true boxes, collides_cloud against the cloud.
  PlanRows plans;
  /// For a picture: the last frame's cloud (x, y, z; at most 20000 of its points) and the last
  /// solved Fastron plan of the last trial (kind "path": the arm's tip along it; "start",
  /// "goal": the arm's link origins from the shoulder to the tip).
  Table scene, path;
};

SensedResults runSensed(const SensedOptions& options, const Progress& progress);
std::string sensedReport(const SensedResults& results, const SensedOptions& options);

}  // namespace fastron::experiments
