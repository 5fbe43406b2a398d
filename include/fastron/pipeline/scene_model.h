#pragma once
// The default method of planning in a scene (what `fastron plan` does, and bench motion-bench's
// "Fastron"): a model of the scene's obstacles alone, trained in the scene, planned on and
// verified and repaired with the exact checker.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/geometry/checker_options.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace FASTRON_API fastron {
namespace pipeline {

/// How a scene's model is trained. Defaults: those of `fastron plan` and bench motion-bench. The
/// training is what a plan with the model must win back, and a smaller model answers faster
/// (verification catches what it gets wrong). With training counted, 1000 samples and no
/// active-learning update planned faster than 2000 samples and one update on six of eight
/// families of four robots, as fast on one and slower on the mobile-arm cage (geometric mean
/// 3.6-3.7x FCL against 2.1-2.3x with one query per scene); 1000 samples with one update, 1500
/// or 600 were in between (docs/log/2026-11-30-fewer-samples-per-scene.md).
struct SceneModelOptions {
  std::size_t samples = 1000;  ///< FCL-labelled uniform configurations
  std::size_t updates = 0;     ///< active-learning updates after them
  std::uint64_t seed = 1;
  std::optional<double> gamma, beta;  ///< kernel width, conditional bias (unset: the features')
  std::string checker{kDefaultSceneChecker};  ///< the oracle's backend (scene_checkers.h)
  /// With several feature candidates: fresh labelled configurations that decide between them.
  std::size_t heldOut = 500;
};

/// Features a scene model may learn on, named for reports ("spread", "cover").
struct FeatureCandidate {
  std::string name;
  FeatureMap features;
};

/// A candidate's model on the held-out configurations.
struct CandidateScore {
  std::string name;
  double accuracy = 0, tpr = 0;
  std::size_t support = 0;
};

/// A model of a scene's obstacles and the checker it learned from.
struct SceneModel {
  /// The exact checker (options.checker) on the scene without self-collision: a relaxation of
  /// the exact checker of verification, which may check self-collision too (self-collisions are
  /// left to verification).
  std::shared_ptr<const SceneChecker> oracle;
  std::unique_ptr<ProxyCollisionDetector> detector;  ///< no band: it plans without one
  double trainSeconds = 0;  ///< labelling and training, every candidate's and the held-out labels
  /// With several candidates: each one's score on the held-out configurations, in their order;
  /// `chosen` indexes the one kept. Empty for a model of one set of features.
  std::vector<CandidateScore> candidates;
  std::size_t chosen = 0;
};

/// The robot's automatic features for a scene model: joint scaling alone, or the control
/// points of the spread rule (robotFeatures' default) and of the cover rule when they differ. On
/// the Panda the spread rule is as good or better, on the validation robots the cover rule far
/// better (docs/log/2026-11-29-control-points-of-scene-models.md).
std::vector<FeatureCandidate> automaticFeatureCandidates(const Robot& robot, FeatureKind kind);

/// Trains the model of `scene`'s obstacles for `robot` on `features` (pipeline::robotProxyParams
/// of their kind, for a scene that stands still, without a band): `options.samples` labelled
/// uniform configurations, then `options.updates` active-learning updates. `checking` is the
/// exact checker's: its padding is the oracle's too.
SceneModel trainSceneModel(const Robot& robot, const Scene& scene, const CheckerOptions& checking,
                           const FeatureMap& features, const SceneModelOptions& options);
/// The same on each of `candidates` (one: as above): `options.samples` uniform configurations
/// labelled once and learned by every candidate, then each one's own `options.updates`; the one
/// whose model scores the highest accuracy + TPR on `options.heldOut` fresh labelled
/// configurations is kept, the first of equals. Throws InvalidArgument on no candidate.
SceneModel trainSceneModel(const Robot& robot, const Scene& scene, const CheckerOptions& checking,
                           const std::vector<FeatureCandidate>& candidates,
                           const SceneModelOptions& options);

/// The default method's plan: on the model, then on a hybrid asking the model's oracle about
/// every "collides", then on `exact`; every path verified and repaired with `exact`
/// (planVerifiedLearning with oracleRelaxesExact).
VerifiedPlan planOnSceneModel(SceneModel& model,
                              const std::shared_ptr<const CollisionChecker>& exact,
                              const JointLimits& limits, const Eigen::VectorXd& start,
                              const Eigen::VectorXd& goal, PlannerOptions options);

/// A scene's obstacle model and the robot's self-collision model (pipeline::selfCollisionModel,
/// asked through pipeline::selfModelChecker) as one checker: in collision when either says so.
/// Named "Fastron+" and the self checker's name. Throws InvalidArgument on a null model or checker,
/// or ones of different joints.
std::shared_ptr<const CollisionChecker> splitModel(std::shared_ptr<const Model> obstacles,
                                                   std::shared_ptr<const CollisionChecker> self);
/// The plan of `fastron plan --self-model` and motion-bench's "Fastron split": on `split`
/// (splitModel), then, as the default method does when its model closes the way, on a hybrid
/// that trusts its "free" and asks `exact` about its "collides" (AllOfChecker), then on `exact`;
/// the path verified and repaired with `exact` (planVerifiedOptimistically).
VerifiedPlan planOnSplitModel(const std::shared_ptr<const CollisionChecker>& split,
                              const std::shared_ptr<const CollisionChecker>& exact,
                              const JointLimits& limits, const Eigen::VectorXd& start,
                              const Eigen::VectorXd& goal, const PlannerOptions& options);

}  // namespace pipeline
}  // namespace fastron
