#include "fastron/pipeline/scene_model.h"

#include <chrono>

#include "fastron/core/model_checker.h"
#include "fastron/pipeline/presets.h"

namespace fastron::pipeline {

SceneModel trainSceneModel(const Robot& robot, const Scene& scene, const CheckerOptions& checking,
                           const FeatureMap& features, const SceneModelOptions& options) {
  SceneModel model;
  CheckerOptions obstaclesOnly = checking;
  obstaclesOnly.selfCollision = false;
  model.oracle = makeSceneChecker(options.checker, robot, scene, obstaclesOnly);
  ProxyParams params =
      withoutBand(forStaticScene(robotProxyParams(features.kind(), 5, 500, options.seed)));
  if (options.gamma) params.train.kernel.gamma = *options.gamma;
  if (options.beta) params.train.beta = *options.beta;
  model.detector = std::make_unique<ProxyCollisionDetector>(model.oracle, features, params);
  model.trainSeconds = std::chrono::duration<double>(
                           trainStatic(*model.detector, options.samples, options.updates).total)
                           .count();
  return model;
}

VerifiedPlan planOnSceneModel(SceneModel& model,
                              const std::shared_ptr<const CollisionChecker>& exact,
                              const JointLimits& limits, const Eigen::VectorXd& start,
                              const Eigen::VectorXd& goal, PlannerOptions options) {
  options.verify.oracleRelaxesExact = true;  // FCL without self-collision: a relaxation of `exact`
  return planVerifiedLearning(*model.detector, exact, limits, start, goal, options);
}

std::shared_ptr<const CollisionChecker> splitModel(std::shared_ptr<const Model> obstacles,
                                                   std::shared_ptr<const Model> self) {
  return std::make_shared<const AnyOfChecker>(std::vector<std::shared_ptr<const CollisionChecker>>{
      std::make_shared<const ModelChecker>(std::move(obstacles)),
      std::make_shared<const ModelChecker>(std::move(self), "Fastron self")});
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
