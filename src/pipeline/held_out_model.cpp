#include "fastron/pipeline/held_out_model.h"

#include <chrono>
#include <memory>
#include <sstream>

#include "fastron/core/error.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/scene_checkers.h"

namespace fastron::pipeline {

std::vector<double> increasingMargins(const std::vector<double>& margins) {
  std::vector<double> used;
  for (const double margin : margins) {
    if (margin == 0) continue;
    if (!used.empty() && margin <= used.back()) {
      std::ostringstream message;
      message << "obstacle margins must increase, got " << used.back() << " then " << margin;
      throw InvalidArgument(message.str());
    }
    used.push_back(margin);
  }
  return used;
}

ControlPointOptions heldOutControlPoints(bool selfCollision) {
  if (selfCollision) return {};
  return {
      .rule = ControlPointRule::Spread, .maxPoints = 10, .maxPerBody = 0, .alongGeometry = true};
}

std::vector<ModelCandidate> moreControlPointCandidates(const Robot& robot,
                                                       const FeatureMap& features,
                                                       const ControlPointOptions& automatic,
                                                       TrainParams params, double beta) {
  if (features.kind() != FeatureKind::Kinematic || automatic.maxPoints == 0) return {};
  params.beta = beta;
  std::vector<ModelCandidate> candidates;
  for (const ControlPointRule rule : {ControlPointRule::Spread, ControlPointRule::Cover}) {
    ControlPointOptions more = automatic;
    ++more.maxPoints;
    more.rule = rule;
    std::vector<ControlPoint> points = defaultControlPoints(robot, more);
    // The same rule with no point more to give would train the first model again.
    if (rule == automatic.rule && points.size() * 3 <= features.featureDim()) continue;
    candidates.push_back({robotFeatures(robot, FeatureKind::Kinematic, std::move(points)), params});
  }
  return candidates;
}

HeldOutModel trainHeldOutModel(const Robot& robot, const Scene& scene, const FeatureMap& features,
                               const TrainParams& params, const HeldOutModelOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  validate(options.targets);  // before any checker is built
  HeldOutModel result;
  // A scene without obstacles has nothing to grow.
  if (scene.size() > 0) result.margins = increasingMargins(options.margins);
  const CheckerOptions checking{.selfCollision = options.selfCollision,
                                .padding = options.padding,
                                .selfPairTables = options.selfPairTables};
  const auto oracle = makeSceneChecker(options.checker, robot, scene, checking);
  std::vector<std::shared_ptr<const SceneChecker>> grown;
  std::vector<const CollisionChecker*> grownOracles;
  for (const double margin : result.margins) {
    grown.push_back(makeSceneChecker(options.checker, robot, scene.grown(margin), checking));
    grownOracles.push_back(grown.back().get());
  }
  if (options.automatic && !options.selfCollision) {
    result.candidates = moreControlPointCandidates(robot, features, *options.automatic, params,
                                                   options.candidateBeta.value_or(kMorePointsBeta));
  }
  result.oracle = oracle->name();
  Rng rng(options.seed);
  result.training =
      trainToHeldOutTargets(*oracle, features, params, options.samples, options.targets, rng,
                            options.threads, grownOracles, result.candidates);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace fastron::pipeline
