#include "fastron/pipeline/scene_model.h"

#include <chrono>
#include <cmath>
#include <utility>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model_checker.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/pipeline/presets.h"
#include "fastron/proxy/labelling.h"

namespace fastron::pipeline {

namespace {

/// The scene's obstacles alone, as the exact checker sees them (its padding too).
std::shared_ptr<const SceneChecker> obstaclesOracle(const Robot& robot, const Scene& scene,
                                                    const CheckerOptions& checking,
                                                    const SceneModelOptions& options) {
  CheckerOptions obstaclesOnly = checking;
  obstaclesOnly.selfCollision = false;
  return makeSceneChecker(options.checker, robot, scene, obstaclesOnly);
}

std::unique_ptr<ProxyCollisionDetector> sceneDetector(std::shared_ptr<const SceneChecker> oracle,
                                                      const FeatureMap& features,
                                                      const SceneModelOptions& options) {
  ProxyParams params =
      withoutBand(forStaticScene(robotProxyParams(features.kind(), 5, 500, options.seed)));
  if (options.gamma) params.train.kernel.gamma = *options.gamma;
  if (options.beta) params.train.beta = *options.beta;
  return std::make_unique<ProxyCollisionDetector>(std::move(oracle), features, params);
}

/// `n` uniform configurations of `limits` labelled by `oracle` on every core.
Dataset labelledSamples(const CollisionChecker& oracle, const JointLimits& limits, std::size_t n,
                        Rng& rng) {
  Dataset data;
  data.points = uniformConfigurations(limits, n, rng);
  data.labels = labelConfigurations(oracle, data.points);
  return data;
}

}  // namespace

SceneModel trainSceneModel(const Robot& robot, const Scene& scene, const CheckerOptions& checking,
                           const FeatureMap& features, const SceneModelOptions& options) {
  SceneModel model;
  model.oracle = obstaclesOracle(robot, scene, checking, options);
  model.detector = sceneDetector(model.oracle, features, options);
  model.trainSeconds = std::chrono::duration<double>(
                           trainStatic(*model.detector, options.samples, options.updates).total)
                           .count();
  return model;
}

SceneModel trainSceneModel(const Robot& robot, const Scene& scene, const CheckerOptions& checking,
                           const std::vector<FeatureCandidate>& candidates,
                           const SceneModelOptions& options) {
  if (candidates.empty()) throw InvalidArgument("trainSceneModel: no feature candidates");
  if (candidates.size() == 1) {
    return trainSceneModel(robot, scene, checking, candidates.front().features, options);
  }
  SceneModel model;
  model.oracle = obstaclesOracle(robot, scene, checking, options);
  // From here, as trainStatic's time in the recipe of one candidate: the oracle's construction
  // (the exact checker's own, on meshes tens of milliseconds) is not training.
  const auto began = std::chrono::steady_clock::now();
  // Its own stream, apart from the detectors' (each seeded from options.seed).
  Rng rng(options.seed ^ 0x5ce9e5a9d1e5ULL);
  const JointLimits& limits = candidates.front().features.limits();
  const Dataset shared = labelledSamples(*model.oracle, limits, options.samples, rng);
  const Dataset heldOut = labelledSamples(*model.oracle, limits, options.heldOut, rng);
  double best = -1;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    auto detector = sceneDetector(model.oracle, candidates[c].features, options);
    detector->initialize(shared);
    for (std::size_t u = 0; u < options.updates; ++u) detector->step();
    const auto trained = detector->model();
    const ConfusionCounts counts = evaluate(*trained, heldOut.points, heldOut.labels);
    // No colliding configuration held out: accuracy alone decides.
    const double tpr = std::isnan(counts.tpr()) ? 1.0 : counts.tpr();
    model.candidates.push_back(
        {candidates[c].name, counts.accuracy(), tpr, trained->supportCount()});
    if (counts.accuracy() + tpr > best) {
      best = counts.accuracy() + tpr;
      model.chosen = c;
      model.detector = std::move(detector);
    }
  }
  model.trainSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  return model;
}

std::vector<FeatureCandidate> automaticFeatureCandidates(const Robot& robot, FeatureKind kind) {
  if (kind != FeatureKind::Kinematic) return {{"joints", robotFeatures(robot, kind)}};
  const std::vector<ControlPoint> spread = defaultControlPoints(robot);
  const std::vector<ControlPoint> cover =
      defaultControlPoints(robot, {.rule = ControlPointRule::Cover});
  std::vector<FeatureCandidate> candidates{{"spread", robotFeatures(robot, kind, spread)}};
  if (cover != spread) candidates.push_back({"cover", robotFeatures(robot, kind, cover)});
  return candidates;
}

VerifiedPlan planOnSceneModel(SceneModel& model,
                              const std::shared_ptr<const CollisionChecker>& exact,
                              const JointLimits& limits, const Eigen::VectorXd& start,
                              const Eigen::VectorXd& goal, PlannerOptions options) {
  options.verify.oracleRelaxesExact = true;  // FCL without self-collision: a relaxation of `exact`
  return planVerifiedLearning(*model.detector, exact, limits, start, goal, options);
}

std::shared_ptr<const CollisionChecker> splitModel(std::shared_ptr<const Model> obstacles,
                                                   std::shared_ptr<const CollisionChecker> self) {
  return std::make_shared<const AnyOfChecker>(std::vector<std::shared_ptr<const CollisionChecker>>{
      std::make_shared<const ModelChecker>(std::move(obstacles)), std::move(self)});
}

VerifiedPlan planOnSplitModel(const std::shared_ptr<const CollisionChecker>& split,
                              const std::shared_ptr<const CollisionChecker>& exact,
                              const JointLimits& limits, const Eigen::VectorXd& start,
                              const Eigen::VectorXd& goal, const PlannerOptions& options) {
  // A conservative self model near an end (a grasp, a folded arm) closes the way as an obstacle
  // model near a wall does; planned on alone, the whole motion then went to `exact`
  // (docs/log/2026-11-25-a-self-collision-model-learned-once.md, "The optimistic hybrid for
  // `--self-model`").
  return planVerifiedOptimistically(split, exact, limits, start, goal, options);
}

}  // namespace fastron::pipeline
