#pragma once
// The most accurate model of a scene that stands still, as `fastron train --robot R --scene S`
// makes it: FCL-labelled samples, then rounds on fresh held-out configurations until the targets
// are met (with the obstacles grown when only the TPR is missed, and with other candidates of
// task-space features), the model closest to the targets kept.

#include <cstdint>
#include <optional>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/core/trainer.h"
#include "fastron/geometry/checker_options.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/scene.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/geometry/self_pair_table.h"
#include "fastron/proxy/held_out_training.h"

namespace FASTRON_API fastron {
namespace pipeline {

/// How trainHeldOutModel trains. Defaults: those of `fastron train --robot R --scene S`.
struct HeldOutModelOptions {
  std::size_t samples = kSceneSamples;  ///< FCL-labelled uniform configurations of the first model
  HeldOutTargets targets;               ///< the rounds' size and targets
  /// Obstacle margins (metres, increasing; zeros ignored) of the labels a round learns when it
  /// meets the target accuracy and misses the TPR.
  std::vector<double> margins{kGrownObstacleMargins.begin(), kGrownObstacleMargins.end()};
  /// Labels of FCL with self-collision (and no grown obstacles or other candidates, which were
  /// measured on obstacles' labels).
  bool selfCollision = false;
  double padding = 0;  ///< grows the robot's shapes in every label (m)
  /// With selfCollision: the robot's self-pair tables for every labelling checker
  /// (CheckerOptions::selfPairTables; pipeline::selfPairTables), or null for none.
  std::shared_ptr<const std::vector<SelfPairTable>> selfPairTables;
  std::string checker{kDefaultSceneChecker};  ///< the labels' exact checker (scene_checkers.h)
  /// The automatic control points that `features` were chosen by, when they were: the rounds
  /// then also try one more point by each rule (otherCandidates). Empty: no other candidates.
  std::optional<ControlPointOptions> automatic;
  /// The other candidates' conditional bias; unset: kMorePointsBeta.
  std::optional<double> candidateBeta;
  std::uint64_t seed = 1;
  unsigned threads = 0;  ///< labelling and Algorithm 1 (0: every core)
};

/// The model and how it was made.
struct HeldOutModel {
  HeldOutTraining training;     ///< the rounds, and the model kept
  std::vector<double> margins;  ///< the margins used (HeldOutRound::grownLevel indexes them)
  std::vector<ModelCandidate> candidates;  ///< the other candidates (HeldOutRound::candidate - 1)
  double seconds = 0;                      ///< labelling and training
  std::string oracle;                      ///< the labels' checker, by its name() ("FCL")
};

/// The automatic control points of the models trainHeldOutModel makes for `fastron train --robot
/// R --scene S` and Python's train_held_out_model: up to 10 by the spread rule, candidates along
/// every link's collision geometry too, no limit per rigid body. Their kernel has point terms
/// alone (sceneTrainParams), which a point field answers with one grid read per point, so points
/// cost little, and terms of single points need points wherever a link can touch: the mesh
/// Panda's box scene went from TPR 0.884 with points at link origins to 0.963 with these
/// (docs/performance.md, "Answers from tabulated point terms"). With `selfCollision` labels the
/// kernel keeps one term (sceneTrainParams), and the points are the defaults
/// (ControlPointOptions{}).
ControlPointOptions heldOutControlPoints(bool selfCollision = false);

/// Margins without zeros; throws InvalidArgument naming the pair unless they increase.
std::vector<double> increasingMargins(const std::vector<double>& margins);

/// The other candidates of the rounds for automatic task-space features: one more control point
/// than `features` has, by the spread rule (when it gives a point more) and by the cover rule,
/// each with `params` and beta `beta`. Empty for joint features.
std::vector<ModelCandidate> moreControlPointCandidates(const Robot& robot,
                                                       const FeatureMap& features,
                                                       const ControlPointOptions& automatic,
                                                       TrainParams params, double beta);

/// Trains a model of `scene` for `robot` on `features` with `params`: options.samples labelled
/// uniform configurations, then held-out rounds (trainToHeldOutTargets) with FCL as the oracle,
/// FCL on the scene grown by each margin for rounds that miss the TPR alone, and the other
/// candidates when options.automatic is set and the labels leave self-collision out. An empty
/// scene with options.selfCollision learns the robot's self-collisions alone (no margins).
/// Throws InvalidArgument on targets out of range or margins that do not increase, before any
/// label is computed.
HeldOutModel trainHeldOutModel(const Robot& robot, const Scene& scene, const FeatureMap& features,
                               const TrainParams& params, const HeldOutModelOptions& options);

}  // namespace pipeline
}  // namespace fastron
