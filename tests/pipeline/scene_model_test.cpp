// The default method's recipe: a model of a scene's obstacles, planned on and verified.

#include "fastron/pipeline/scene_model.h"

#include <gtest/gtest.h>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/pipeline/self_model.h"
#include "fastron/planning/motion.h"
#include "fastron/planning/planner.h"

namespace fastron::pipeline {
namespace {

Scene oneBox() {
  Scene scene;
  scene.add({"box", Box{Eigen::Vector3d(0.3, 0.3, 0.3)}, makePose({0.6, -0.5, 0.3}), std::nullopt});
  return scene;
}

/// Baxter's model of oneBox(), as the plan tests train it.
SceneModel baxterModelOfOneBox(const Robot& baxter) {
  return trainSceneModel(baxter, oneBox(), {}, robotFeatures(baxter, FeatureKind::Kinematic),
                         {.samples = 1500, .updates = 1, .seed = 1, .gamma = {}, .beta = {}});
}

/// The plan tests' start (shoulder -1.2) and goal (1.2), on either side of the box.
Eigen::VectorXd baxterEnd(double shoulder) {
  Eigen::VectorXd q(7);
  q << shoulder, 0.3, 0, 1.2, 0, 0.5, 0;
  return q;
}

// The same seed gives the same model (the command and the experiments call this one recipe);
// with self-collision checked, the model learns the obstacles alone: its oracle checks none.
TEST(SceneModel, TheSameSeedGivesTheSameModelOfTheObstaclesAlone) {
  const Robot baxter = loadRobot("baxter");
  const Scene scene = oneBox();
  const FeatureMap features = robotFeatures(baxter, FeatureKind::Kinematic);
  const SceneModelOptions options{
      .samples = 1500, .updates = 1, .seed = 3, .gamma = {}, .beta = {}};
  SceneModel a = trainSceneModel(baxter, scene, {.selfCollision = true}, features, options);
  SceneModel b = trainSceneModel(baxter, scene, {.selfCollision = true}, features, options);
  EXPECT_GT(a.trainSeconds, 0);
  Rng rng(9);
  const Configurations q = uniformConfigurations(baxter.limits(), 400, rng);
  EXPECT_EQ(a.detector->model()->scoreBatch(q), b.detector->model()->scoreBatch(q));
  EXPECT_EQ(a.detector->model()->supportCount(), b.detector->model()->supportCount());
  const FclChecker obstaclesOnly(baxter, scene);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const std::span<const double> c(q.row(i).data(), baxter.dof());
    EXPECT_EQ(a.oracle->inCollision(c), obstaclesOnly.inCollision(c));
  }
  SceneModelOptions wider = options;
  wider.gamma = 5;
  EXPECT_EQ(trainSceneModel(baxter, scene, {}, features, wider).detector->model()->kernel().gamma,
            5);
}

// Candidates learn one labelling, each makes its own update, and the one that scores best on
// held-out labels is kept: a control point on Baxter's shoulder (it barely moves) cannot tell
// where the arm meets the box, the automatic points can, whichever order they come in. One
// candidate is the plain recipe.
TEST(SceneModel, KeepsTheCandidateThatScoresBestOnHeldOutLabels) {
  const Robot baxter = loadRobot("baxter");
  const Scene scene = oneBox();
  const FeatureMap automatic = robotFeatures(baxter, FeatureKind::Kinematic);
  const FeatureMap shoulder =
      robotFeatures(baxter, FeatureKind::Kinematic, {{"right_upper_shoulder", {0, 0, 0}}});
  const SceneModelOptions options{.samples = 1500,
                                  .updates = 1,
                                  .seed = 2,
                                  .gamma = {},
                                  .beta = {},
                                  .checker = std::string(kDefaultSceneChecker),
                                  .heldOut = 400};
  const std::vector<FeatureCandidate> both{{"shoulder", shoulder}, {"automatic", automatic}};
  for (const bool reversed : {false, true}) {
    const std::vector<FeatureCandidate> candidates =
        reversed ? std::vector<FeatureCandidate>{both[1], both[0]} : both;
    const SceneModel model = trainSceneModel(baxter, scene, {}, candidates, options);
    ASSERT_EQ(model.candidates.size(), 2u);
    EXPECT_EQ(model.candidates[0].name, candidates[0].name);
    EXPECT_EQ(model.candidates[model.chosen].name, "automatic");
    const CandidateScore& worse = model.candidates[1 - model.chosen];
    const CandidateScore& kept = model.candidates[model.chosen];
    EXPECT_GT(kept.accuracy + kept.tpr, worse.accuracy + worse.tpr);
    EXPECT_EQ(model.detector->features().kinematics()->description().points,
              automatic.kinematics()->description().points);
    EXPECT_EQ(kept.support, model.detector->model()->supportCount());
    EXPECT_GT(model.trainSeconds, 0);
    // What the held-out labels said holds on fresh ones.
    Rng rng(11);
    const Configurations q = uniformConfigurations(baxter.limits(), 2000, rng);
    const FclChecker fcl(baxter, scene);
    Labels truth;
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      truth.push_back(fcl.inCollision(std::span<const double>(q.row(i).data(), 7)) ? 1 : -1);
    }
    EXPECT_GT(evaluate(*model.detector->model(), q, truth).accuracy(), 0.9);
  }

  const SceneModel one = trainSceneModel(baxter, scene, {}, {{"automatic", automatic}}, options);
  const SceneModel plain = trainSceneModel(baxter, scene, {}, automatic, options);
  EXPECT_TRUE(one.candidates.empty());
  Rng rng(12);
  const Configurations q = uniformConfigurations(baxter.limits(), 300, rng);
  EXPECT_EQ(one.detector->model()->scoreBatch(q), plain.detector->model()->scoreBatch(q));
  EXPECT_THROW(trainSceneModel(baxter, scene, {}, std::vector<FeatureCandidate>{}, options),
               InvalidArgument);
}

// The automatic candidates: the spread rule's points (robotFeatures' own) and the cover rule's
// where they differ; joint features alone for joints.
TEST(SceneModel, AutomaticCandidatesAreTheSpreadAndCoverRulesPoints) {
  const Robot arm = loadRobot("mobile-arm");
  const std::vector<FeatureCandidate> candidates =
      automaticFeatureCandidates(arm, FeatureKind::Kinematic);
  ASSERT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0].name, "spread");
  EXPECT_EQ(candidates[1].name, "cover");
  EXPECT_EQ(candidates[0].features.kinematics()->description().points, defaultControlPoints(arm));
  EXPECT_EQ(candidates[1].features.kinematics()->description().points,
            defaultControlPoints(arm, {.rule = ControlPointRule::Cover}));
  const std::vector<FeatureCandidate> joints =
      automaticFeatureCandidates(arm, FeatureKind::JointScaling);
  ASSERT_EQ(joints.size(), 1u);
  EXPECT_EQ(joints[0].features.kind(), FeatureKind::JointScaling);
}

// Its plans are verified with the exact checker at the plan's resolution, as every final path
// is (an independent FCL checker audits it there, as the experiments do).
TEST(SceneModel, ItsPlansAreFreeUnderTheExactChecker) {
  const Robot baxter = loadRobot("baxter");
  const Scene scene = oneBox();
  SceneModel model = baxterModelOfOneBox(baxter);
  const auto exact = std::make_shared<const FclChecker>(baxter, scene);
  const Eigen::VectorXd start = baxterEnd(-1.2), goal = baxterEnd(1.2);
  seedPlanners(1, 0);
  const VerifiedPlan plan = planOnSceneModel(model, exact, baxter.limits(), start, goal,
                                             {.resolution = 0.03, .timeLimit = 10});
  ASSERT_TRUE(plan.solved()) << plan.failure;
  const FclChecker audit(baxter, scene);
  EXPECT_TRUE(checkPath(audit, plan.path, 0.03).valid());
}

// The split plan: a "self model" that calls the start colliding (as the Panda's did on a cage
// request) leaves the models' plan nowhere to go; the hybrid after it asks FCL about what they
// call colliding, and the path it finds is free under FCL.
TEST(SceneModel, ASplitModelThatEnclosesAnEndStillPlans) {
  const Robot baxter = loadRobot("baxter");
  const Scene scene = oneBox();
  SceneModel model = baxterModelOfOneBox(baxter);
  const Eigen::VectorXd start = baxterEnd(-1.2), goal = baxterEnd(1.2);
  // One support point at the start with a large weight: "colliding" within a kernel width of it.
  const auto self = std::make_shared<const Model>(
      FeatureMap::jointScaling(baxter.limits()), Kernel{KernelType::RationalQuadratic, 5},
      Configurations(start.transpose()), Eigen::VectorXd::Constant(1, 10.0));
  ASSERT_TRUE(self->inCollision(start.data()));
  const auto split = splitModel(model.detector->model(), selfModelChecker(baxter, self));
  EXPECT_EQ(split->name(), "Fastron+Fastron self");
  const auto exact = std::make_shared<const FclChecker>(baxter, scene);
  seedPlanners(1, 0);
  const VerifiedPlan plan = planOnSplitModel(split, exact, baxter.limits(), start, goal,
                                             {.resolution = 0.03, .timeLimit = 10});
  ASSERT_TRUE(plan.solved()) << plan.failure;
  ASSERT_GE(plan.attempts.size(), 2u);
  EXPECT_EQ(plan.attempts[0].status, PlanStatus::InvalidStart);
  EXPECT_EQ(plan.attempts[1].source, "Fastron+Fastron self&FCL");
  const FclChecker audit(baxter, scene);
  EXPECT_TRUE(checkPath(audit, plan.path, 0.03).valid());
  EXPECT_THROW(splitModel(model.detector->model(), nullptr), InvalidArgument);
}

}  // namespace
}  // namespace fastron::pipeline
