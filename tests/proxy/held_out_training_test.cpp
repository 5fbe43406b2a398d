// Training a static scene's model until fresh configurations meet the targets.

#include "fastron/proxy/held_out_training.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "test_worlds.h"

namespace fastron {
namespace {

constexpr std::size_t kDim = 3;

TrainParams ballParams() {
  TrainParams p;
  p.kernel.gamma = 30;
  p.beta = 5;
  p.maxSupportPoints = 100000;
  return p;
}

/// Labels without structure: about one configuration in five collides, at random.
struct NoiseOracle {
  FunctionChecker checker{"noise", kDim, [](const double* q) {
                            return std::hash<double>{}(q[0] * 7.3 + q[1] * 3.1 + q[2]) % 5 == 0;
                          }};
};

struct BallOracle {
  test::BallWorld world = test::BallWorld::random(kDim, 8, 0.3, 5);
  FunctionChecker checker{"balls", kDim, [this](const double* q) { return world.inCollision(q); }};
};

TEST(HeldOutTraining, StopsAtTheFirstRoundThatMeetsTheTargets) {
  const BallOracle oracle;
  Rng rng(1);
  const HeldOutTraining trained =
      trainToHeldOutTargets(oracle.checker, FeatureMap::jointScaling(JointLimits::unitBox(kDim)),
                            ballParams(), 1500, {.accuracy = 0.5, .truePositiveRate = 0.5}, rng);
  ASSERT_EQ(trained.rounds.size(), 1u);
  EXPECT_EQ(trained.rounds[0].trainingSamples, 1500u);
  EXPECT_EQ(trained.rounds[0].supportCount, trained.model->supportCount());
  EXPECT_EQ(trained.rounds[0].heldOut.total(), HeldOutTargets{}.samplesPerRound);
}

/// What a round's counts lack of the targets (the rule trainToHeldOutTargets keeps by).
double lacking(const ConfusionCounts& c, const HeldOutTargets& t) {
  return std::max(0.0, t.accuracy - c.accuracy()) + std::max(0.0, t.truePositiveRate - c.tpr());
}

TEST(HeldOutTraining, LearnsEachRoundAndMeasuresEveryModelOnConfigurationsItNeverLearned) {
  const BallOracle oracle;
  const FeatureMap features = FeatureMap::jointScaling(JointLimits::unitBox(kDim));
  const HeldOutTargets unreachable{
      .accuracy = 1, .truePositiveRate = 1, .samplesPerRound = 1000, .maxTrainingSamples = 2200};
  Rng rng(2);
  const Rng start = rng;
  const HeldOutTraining trained =
      trainToHeldOutTargets(oracle.checker, features, ballParams(), 200, unreachable, rng);
  // 200, then 1200, then 2200 learned: a fourth model would pass maxTrainingSamples.
  ASSERT_EQ(trained.rounds.size(), 3u);
  EXPECT_EQ(trained.rounds[0].trainingSamples, 200u);
  EXPECT_EQ(trained.rounds[1].trainingSamples, 1200u);
  EXPECT_EQ(trained.rounds[2].trainingSamples, 2200u);
  // From 200 samples to 2200, the held-out accuracy of eight balls in 3-D rises clearly, and the
  // model kept is the last one.
  EXPECT_GT(trained.rounds[2].heldOut.accuracy(), trained.rounds[0].heldOut.accuracy() + 0.03)
      << trained.rounds[0].heldOut.accuracy() << " " << trained.rounds[1].heldOut.accuracy();
  ASSERT_EQ(trained.chosenRound, 2u);

  // The same draws, independently: the kept model is Algorithm 1 on the initial samples and the
  // first two rounds' configurations, measured on the third round's.
  Rng replay = start;
  Configurations learned = uniformConfigurations(features.limits(), 200, replay);
  for (int r = 0; r < 2; ++r) {
    const Configurations fresh = uniformConfigurations(features.limits(), 1000, replay);
    learned.conservativeResize(learned.rows() + fresh.rows(), Eigen::NoChange);
    learned.bottomRows(fresh.rows()) = fresh;
  }
  const Configurations last = uniformConfigurations(features.limits(), 1000, replay);
  Trainer trainer(features, ballParams());
  trainer.addPoints(learned, oracle.world.label(learned));
  trainer.update();
  EXPECT_EQ(trainer.model()->weights(), trained.model->weights());
  const ConfusionCounts measured = evaluate(*trained.model, last, oracle.world.label(last));
  EXPECT_EQ(measured.truePositives, trained.rounds[2].heldOut.truePositives);
  EXPECT_EQ(measured.falseNegatives, trained.rounds[2].heldOut.falseNegatives);
  EXPECT_EQ(measured.falsePositives, trained.rounds[2].heldOut.falsePositives);
}

TEST(HeldOutTraining, KeepsTheRoundClosestToTheTargets) {
  // Labels without structure: no round learns anything that holds on fresh configurations, so
  // which round comes closest is chance, and the one kept must be it.
  const NoiseOracle noise;
  const HeldOutTargets targets{.samplesPerRound = 500, .maxTrainingSamples = 2500};
  Rng rng(6);
  const HeldOutTraining trained =
      trainToHeldOutTargets(noise.checker, FeatureMap::jointScaling(JointLimits::unitBox(kDim)),
                            ballParams(), 500, targets, rng);
  ASSERT_EQ(trained.rounds.size(), 5u);
  for (const HeldOutRound& round : trained.rounds) {
    EXPECT_LE(lacking(trained.rounds[trained.chosenRound].heldOut, targets),
              lacking(round.heldOut, targets));
  }
  EXPECT_EQ(trained.model->supportCount(), trained.rounds[trained.chosenRound].supportCount);
}

TEST(HeldOutTraining, StopsWhenTheModelIsAtItsSupportCap) {
  const BallOracle oracle;
  TrainParams capped = ballParams();
  capped.maxSupportPoints = 20;
  Rng rng(7);
  const HeldOutTraining trained =
      trainToHeldOutTargets(oracle.checker, FeatureMap::jointScaling(JointLimits::unitBox(kDim)),
                            capped, 2000, {.accuracy = 1, .truePositiveRate = 1}, rng);
  ASSERT_EQ(trained.rounds.size(), 1u);
  EXPECT_EQ(trained.update.stopReason, StopReason::SupportCap);
}

TEST(HeldOutTraining, ASceneWithoutCollisionsHasNoTprToMiss) {
  const FunctionChecker free("free", kDim, [](const double*) { return false; });
  Rng rng(3);
  const HeldOutTraining trained = trainToHeldOutTargets(
      free, FeatureMap::jointScaling(JointLimits::unitBox(kDim)), ballParams(), 500, {}, rng);
  ASSERT_EQ(trained.rounds.size(), 1u);
  EXPECT_EQ(trained.rounds[0].heldOut.accuracy(), 1.0);
}

TEST(HeldOutTraining, ARoundThatMissesOnlyTheTprLearnsTheNextGrownOraclesLabels) {
  const BallOracle oracle;
  // The most room there is: every configuration collides.
  const FunctionChecker everywhere("everywhere", kDim, [](const double*) { return true; });
  const std::vector<const CollisionChecker*> grown{&everywhere};
  const HeldOutTargets targets{.accuracy = 0, .truePositiveRate = 1, .samplesPerRound = 1000};
  Rng rng(5);
  const HeldOutTraining trained =
      trainToHeldOutTargets(oracle.checker, FeatureMap::jointScaling(JointLimits::unitBox(kDim)),
                            ballParams(), 1000, targets, rng, 0, grown);
  ASSERT_EQ(trained.rounds.size(), 2u);
  EXPECT_EQ(trained.rounds[0].grownLevel, 0u);
  ASSERT_LT(trained.rounds[0].heldOut.tpr(), 1.0);
  // The second round learned the first's configurations and its fresh ones, all as collisions.
  EXPECT_EQ(trained.rounds[1].grownLevel, 1u);
  EXPECT_EQ(trained.rounds[1].trainingSamples, 2000u);
  // ... and was measured on the oracle's labels: its model calls everything a collision, so the
  // free configurations are its false positives, not true positives as the grown labels say.
  const ConfusionCounts& second = trained.rounds[1].heldOut;
  EXPECT_EQ(second.tpr(), 1.0);
  EXPECT_EQ(second.trueNegatives, 0u);
  EXPECT_GT(second.falsePositives, second.truePositives);
  EXPECT_EQ(trained.chosenRound, 1u);
}

TEST(HeldOutTraining, GrowsNoFurtherThanItsOraclesNorWhenTheAccuracyMisses) {
  const NoiseOracle noise;
  const std::vector<const CollisionChecker*> grown{&noise.checker, &noise.checker};
  const FeatureMap features = FeatureMap::jointScaling(JointLimits::unitBox(kDim));
  const auto levels = [&](HeldOutTargets targets) {
    targets.samplesPerRound = 500;
    targets.maxTrainingSamples = 2500;
    Rng rng(6);
    const HeldOutTraining trained =
        trainToHeldOutTargets(noise.checker, features, ballParams(), 500, targets, rng, 0, grown);
    std::vector<std::size_t> result;
    for (const HeldOutRound& round : trained.rounds) result.push_back(round.grownLevel);
    return result;
  };
  using Levels = std::vector<std::size_t>;
  EXPECT_EQ(levels({.accuracy = 0, .truePositiveRate = 1}), (Levels{0, 1, 2, 2, 2}));
  EXPECT_EQ(levels({.accuracy = 1, .truePositiveRate = 0}), (Levels{0, 0, 0, 0, 0}));
}

TEST(HeldOutTraining, RejectsANullOrMismatchedGrownOracle) {
  const BallOracle oracle;
  const FunctionChecker twoJoints("two", 2, [](const double*) { return true; });
  const FeatureMap features = FeatureMap::jointScaling(JointLimits::unitBox(kDim));
  Rng rng(4);
  const auto train = [&](const CollisionChecker* grown) {
    const std::vector<const CollisionChecker*> oracles{grown};
    return trainToHeldOutTargets(oracle.checker, features, ballParams(), 100, {}, rng, 0, oracles);
  };
  EXPECT_THROW(train(nullptr), InvalidArgument);
  try {
    train(&twoJoints);
    FAIL() << "a grown oracle with 2 joints was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("2 joints, the oracle 3"), std::string::npos) << e.what();
  }
}

TEST(HeldOutTraining, AnAlternativeLearnsTheSameSamplesWhenTheFirstMissesAndTheCloserIsKept) {
  const BallOracle oracle;
  const FeatureMap features = FeatureMap::jointScaling(JointLimits::unitBox(kDim));
  // The first way stops Algorithm 1 after three iterations: three support points cannot describe
  // eight balls, so it misses the accuracy target; the usual parameters meet it.
  TrainParams stopped = ballParams();
  stopped.maxIterations = 3;
  const std::vector<ModelCandidate> alternatives{{features, ballParams()}};
  const HeldOutTargets targets{.accuracy = 0.85, .truePositiveRate = 0.8, .samplesPerRound = 1000};
  Rng rng(8);
  const Rng start = rng;
  const HeldOutTraining trained = trainToHeldOutTargets(oracle.checker, features, stopped, 1500,
                                                        targets, rng, 0, {}, alternatives);
  // One round, two candidates, measured on the same 1000 fresh configurations; the alternative
  // met the targets, so no second round.
  ASSERT_EQ(trained.rounds.size(), 2u);
  EXPECT_EQ(trained.rounds[0].candidate, 0u);
  EXPECT_EQ(trained.rounds[1].candidate, 1u);
  EXPECT_EQ(trained.rounds[1].trainingSamples, 1500u);
  EXPECT_EQ(trained.rounds[1].heldOut.total(), 1000u);
  EXPECT_EQ(trained.rounds[0].heldOut.truePositives + trained.rounds[0].heldOut.falseNegatives,
            trained.rounds[1].heldOut.truePositives + trained.rounds[1].heldOut.falseNegatives);
  EXPECT_LT(trained.rounds[0].heldOut.accuracy(), targets.accuracy);
  EXPECT_GE(trained.rounds[1].heldOut.accuracy(), targets.accuracy);
  EXPECT_EQ(trained.chosenRound, 1u);
  EXPECT_EQ(trained.update.supportCount, trained.model->supportCount());
  // The model kept is Algorithm 1 with the alternative's parameters on the first round's samples.
  Rng replay = start;
  const Configurations learned = uniformConfigurations(features.limits(), 1500, replay);
  Trainer trainer(features, ballParams());
  trainer.addPoints(learned, oracle.world.label(learned));
  trainer.update();
  EXPECT_EQ(trainer.model()->weights(), trained.model->weights());
}

TEST(HeldOutTraining, AnAlternativeIsNotTrainedWhenTheFirstMeetsTheTargets) {
  const BallOracle oracle;
  const FeatureMap features = FeatureMap::jointScaling(JointLimits::unitBox(kDim));
  const std::vector<ModelCandidate> alternatives{{features, ballParams()}};
  Rng rng(1);
  const HeldOutTraining trained =
      trainToHeldOutTargets(oracle.checker, features, ballParams(), 1500,
                            {.accuracy = 0.5, .truePositiveRate = 0.5}, rng, 0, {}, alternatives);
  ASSERT_EQ(trained.rounds.size(), 1u);
  EXPECT_EQ(trained.rounds[0].candidate, 0u);
}

TEST(HeldOutTraining, AlternativesAreTriedEveryRoundThatMisses) {
  // Labels without structure: no candidate meets the targets, so every round trains both, and
  // the one kept is the closest of all.
  const NoiseOracle noise;
  const FeatureMap features = FeatureMap::jointScaling(JointLimits::unitBox(kDim));
  TrainParams wide = ballParams();
  wide.kernel.gamma = 3;
  const std::vector<ModelCandidate> alternatives{{features, wide}};
  const HeldOutTargets targets{.samplesPerRound = 500, .maxTrainingSamples = 1500};
  Rng rng(6);
  const HeldOutTraining trained = trainToHeldOutTargets(noise.checker, features, ballParams(), 500,
                                                        targets, rng, 0, {}, alternatives);
  ASSERT_EQ(trained.rounds.size(), 6u);
  for (std::size_t r = 0; r < trained.rounds.size(); ++r) {
    EXPECT_EQ(trained.rounds[r].candidate, r % 2);
    EXPECT_EQ(trained.rounds[r].trainingSamples, 500 + r / 2 * 500);
    EXPECT_LE(lacking(trained.rounds[trained.chosenRound].heldOut, targets),
              lacking(trained.rounds[r].heldOut, targets));
  }
}

TEST(HeldOutTraining, RejectsAnAlternativeOfOtherJoints) {
  const BallOracle oracle;
  const FeatureMap features = FeatureMap::jointScaling(JointLimits::unitBox(kDim));
  const std::vector<ModelCandidate> twoJoints{
      {FeatureMap::jointScaling(JointLimits::unitBox(2)), ballParams()}};
  Rng rng(4);
  try {
    trainToHeldOutTargets(oracle.checker, features, ballParams(), 100, {}, rng, 0, {}, twoJoints);
    FAIL() << "an alternative of 2 joints was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("reads 2 joint values, the first 3"), std::string::npos)
        << e.what();
  }
  TrainParams bad = ballParams();
  bad.kernel.gamma = -1;
  const std::vector<ModelCandidate> badParams{{features, bad}};
  EXPECT_THROW(
      trainToHeldOutTargets(oracle.checker, features, ballParams(), 100, {}, rng, 0, {}, badParams),
      InvalidArgument);
}

TEST(HeldOutTraining, RejectsBadTargets) {
  const BallOracle oracle;
  const FeatureMap features = FeatureMap::jointScaling(JointLimits::unitBox(kDim));
  Rng rng(4);
  const auto train = [&](HeldOutTargets targets, std::size_t initial = 100) {
    return trainToHeldOutTargets(oracle.checker, features, ballParams(), initial, targets, rng);
  };
  EXPECT_THROW(train({.accuracy = 1.5}), InvalidArgument);
  EXPECT_THROW(train({.truePositiveRate = -0.1}), InvalidArgument);
  EXPECT_THROW(train({.accuracy = std::nan("")}), InvalidArgument);
  EXPECT_THROW(train({.samplesPerRound = 0}), InvalidArgument);
  EXPECT_THROW(train({}, 0), InvalidArgument);
}

}  // namespace
}  // namespace fastron
