// fastron train --scene's recipe: held-out rounds with grown obstacles and other candidates.

#include "fastron/pipeline/held_out_model.h"

#include <gtest/gtest.h>

#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/proxy/labelling.h"

namespace fastron::pipeline {
namespace {

TEST(HeldOutModel, MarginsMustIncreaseAndZerosAreDropped) {
  EXPECT_EQ(increasingMargins({0, 0.005, 0.01}), (std::vector<double>{0.005, 0.01}));
  EXPECT_TRUE(increasingMargins({}).empty());
  try {
    increasingMargins({0.02, 0.01});
    FAIL() << "decreasing margins were taken";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "obstacle margins must increase, got 0.02 then 0.01");
  }
}

// One more control point by each rule, with the candidates' beta; none for joint features.
TEST(HeldOutModel, CandidatesHaveOneMoreControlPoint) {
  const Robot baxter = loadRobot("baxter");
  const FeatureMap features = robotFeatures(baxter, FeatureKind::Kinematic);
  const TrainParams params = sceneTrainParams(FeatureKind::Kinematic);
  const auto candidates =
      moreControlPointCandidates(baxter, features, ControlPointOptions{}, params, 7);
  ASSERT_FALSE(candidates.empty());
  for (const ModelCandidate& c : candidates) {
    EXPECT_EQ(c.features.featureDim(), features.featureDim() + 3);
    EXPECT_EQ(c.params.beta, 7);
    EXPECT_EQ(c.params.kernel.gamma, params.kernel.gamma);
  }
  EXPECT_TRUE(moreControlPointCandidates(baxter, robotFeatures(baxter, FeatureKind::JointScaling),
                                         ControlPointOptions{}, params, 7)
                  .empty());
}

// Rounds that cannot meet an accuracy of 1 run to the sample limit, try the candidates, and keep
// the round whose model measured closest to the targets; that model is measured again on fresh
// configurations as a round measured it (up to sampling).
TEST(HeldOutModel, KeepsTheRoundClosestToTheTargets) {
  const Robot baxter = loadRobot("baxter");
  const Scene scene = loadScene(dataDirectory() / "scenes" / "baxter_three_boxes.yaml");
  const FeatureMap features = robotFeatures(baxter, FeatureKind::Kinematic);
  HeldOutModelOptions options;
  options.samples = 1000;
  options.targets = {1.0, 0.96, 1000, 2000};
  options.automatic = ControlPointOptions{};
  options.seed = 3;
  const HeldOutModel made =
      trainHeldOutModel(baxter, scene, features, sceneTrainParams(FeatureKind::Kinematic), options);
  const HeldOutTraining& t = made.training;
  ASSERT_TRUE(t.model);
  EXPECT_EQ(made.margins, (std::vector<double>{0.005, 0.01}));
  EXPECT_FALSE(made.candidates.empty());
  ASSERT_EQ(t.rounds.size(), 2 * (1 + made.candidates.size()));  // two rounds, every candidate
  const HeldOutRound& kept = t.rounds[t.chosenRound];
  EXPECT_EQ(kept.supportCount, t.model->supportCount());
  for (const HeldOutRound& r : t.rounds) {
    const auto lack = [](const ConfusionCounts& c) {
      return (1.0 - c.accuracy()) + std::max(0.0, 0.96 - c.tpr());
    };
    EXPECT_LE(lack(kept.heldOut), lack(r.heldOut));
  }
  // The same options give the same model.
  const HeldOutModel again =
      trainHeldOutModel(baxter, scene, features, sceneTrainParams(FeatureKind::Kinematic), options);
  EXPECT_EQ(again.training.model->checksum(), t.model->checksum());
  HeldOutModelOptions badTargets = options;
  badTargets.targets.accuracy = 1.5;
  EXPECT_THROW(trainHeldOutModel(baxter, scene, features, sceneTrainParams(FeatureKind::Kinematic),
                                 badTargets),
               InvalidArgument);
  options.margins = {0.01, 0.005};
  EXPECT_THROW(
      trainHeldOutModel(baxter, scene, features, sceneTrainParams(FeatureKind::Kinematic), options),
      InvalidArgument);
}

}  // namespace
}  // namespace fastron::pipeline
