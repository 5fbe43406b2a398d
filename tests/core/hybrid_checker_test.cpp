#include "fastron/core/hybrid_checker.h"

#include <gtest/gtest.h>

#include <limits>

#include "fastron/core/error.h"
#include "fastron/core/trainer.h"
#include "fastron/core/uncertainty_band.h"
#include "test_worlds.h"

namespace fastron {
namespace {

constexpr std::size_t kDim = 3;

/// A model of a seeded ball world that misses about 6% of its colliding configurations (beta 1,
/// 3000 points), so the band has work to do, and the world as the exact checker.
struct World {
  test::BallWorld balls = test::BallWorld::random(kDim, 4, 0.5, 7);
  std::shared_ptr<const FunctionChecker> exact = std::make_shared<FunctionChecker>(
      "balls", kDim, [this](const double* q) { return balls.inCollision(q); });
  std::shared_ptr<const Model> model;

  World() {
    TrainParams p;
    p.kernel.gamma = 10;
    p.beta = 1;
    Trainer trainer(JointLimits::unitBox(kDim), p);
    const Configurations q = test::uniformPoints(3000, kDim, 8);
    trainer.addPoints(q, balls.label(q));
    trainer.update();
    model = trainer.model();
  }

  BandCalibration calibrate(std::size_t n, std::uint64_t seed, BandTargets targets = {}) const {
    const Configurations q = test::uniformPoints(n, kDim, seed);
    return calibrateBand(model->scoreBatch(q), balls.label(q), targets);
  }
};

TEST(UncertaintyBand, CalibrationMeetsItsTargetOnUnseenConfigurations) {
  const World world;
  const BandCalibration c = world.calibrate(20000, 9);
  ASSERT_GT(c.colliding, 2000u);
  EXPECT_GT(c.modelMissRate, 0.02) << "the model must miss for the test to mean anything";
  EXPECT_LE(c.bandMissRate, 0.005);
  EXPECT_LT(c.band.lower, 0);
  EXPECT_GE(c.band.upper, 0);
  EXPECT_GT(c.exactShare, 0);
  EXPECT_LT(c.exactShare, 0.5);

  // On configurations the calibration never saw, the share of colliding ones scored below the
  // band stays near the target (20000 fresh ones: a binomial 0.5% varies by about 0.1%).
  const Configurations fresh = test::uniformPoints(20000, kDim, 10);
  const Eigen::VectorXd scores = world.model->scoreBatch(fresh);
  const Labels truth = world.balls.label(fresh);
  std::size_t colliding = 0, missed = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (truth[i] != 1) continue;
    ++colliding;
    if (scores[static_cast<Eigen::Index>(i)] < c.band.lower) ++missed;
  }
  EXPECT_LT(static_cast<double>(missed) / static_cast<double>(colliding), 0.01);
}

TEST(UncertaintyBand, RatesOfZeroAndOneAndMissingClasses) {
  const Eigen::VectorXd scores = (Eigen::VectorXd(6) << -3, -1, 2, -2, 0.5, 4).finished();
  const Labels labels = {1, 1, 1, -1, -1, -1};
  // Miss rate 0: below every colliding score; false alarms 0: above every free score.
  BandCalibration c = calibrateBand(scores, labels, {0, 0});
  EXPECT_EQ(c.band.lower, -3);
  EXPECT_EQ(c.band.upper, 4);
  EXPECT_DOUBLE_EQ(c.bandMissRate, 0);
  EXPECT_DOUBLE_EQ(c.modelMissRate, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(c.exactShare, 1);
  // Rates of 1: the model's own boundary on both sides.
  c = calibrateBand(scores, labels, {1, 1});
  EXPECT_EQ(c.band.lower, 0);
  EXPECT_EQ(c.band.upper, 0);
  // Only free configurations: no evidence below, the boundary stays.
  c = calibrateBand(Eigen::VectorXd::Constant(3, -1.0), {-1, -1, -1}, {});
  EXPECT_EQ(c.band.lower, 0);
  EXPECT_EQ(c.colliding, 0u);
  EXPECT_EQ(calibrateBand(Eigen::VectorXd(0), {}, {}).exactShare, 0);
}

TEST(UncertaintyBand, RefusesBadInput) {
  const Eigen::VectorXd two = Eigen::VectorXd::Zero(2);
  EXPECT_THROW(calibrateBand(two, {1}, {}), InvalidArgument);
  EXPECT_THROW(calibrateBand(two, {1, 0}, {}), InvalidArgument);
  EXPECT_THROW(calibrateBand((Eigen::VectorXd(2) << 0, NAN).finished(), {1, -1}, {}),
               InvalidArgument);
  EXPECT_THROW(calibrateBand(two, {1, -1}, {-0.1, 0}), InvalidArgument);
  EXPECT_THROW(calibrateBand(two, {1, -1}, {0, 1.5}), InvalidArgument);
}

// Outside the band the model answers, inside it the exact checker: a free answer from the model
// inside the band never happens, which the count of exact calls proves configuration by
// configuration.
TEST(HybridChecker, AnswersFromTheModelOnlyOutsideTheBand) {
  const World world;
  const UncertaintyBand band = world.calibrate(5000, 11).band;
  const HybridChecker hybrid(world.model, world.exact, band);
  EXPECT_EQ(hybrid.name(), "Fastron+balls");
  const Configurations q = test::uniformPoints(3000, kDim, 12);
  std::size_t inBand = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const double* row = q.row(i).data();
    const double s = world.model->score(row);
    const std::uint64_t before = world.exact->callCount();
    const bool answer = hybrid.inCollision({row, kDim});
    if (band.contains(s)) {
      ++inBand;
      EXPECT_EQ(world.exact->callCount(), before + 1) << "row " << i;
      EXPECT_EQ(answer, world.balls.inCollision(row)) << "row " << i;
    } else {
      EXPECT_EQ(world.exact->callCount(), before) << "row " << i;
      EXPECT_EQ(answer, s > band.upper) << "row " << i;
    }
  }
  EXPECT_GT(inBand, 0u);
  EXPECT_EQ(hybrid.exactAnswers(), inBand);
  EXPECT_EQ(hybrid.modelAnswers() + hybrid.exactAnswers(), 3000u);
  EXPECT_DOUBLE_EQ(hybrid.exactShare(), static_cast<double>(inBand) / 3000.0);
}

// The batch path an edge check takes answers exactly as configuration after configuration, and
// counts the same answers (model, exact, and the exact checker's calls), also across chunks of
// sixteen and with the band that asks about every "collides" (planVerifiedLearning's hybrid),
// although it asks the exact checker a chunk's states inside the band together.
TEST(HybridChecker, FirstInCollisionAgreesWithSingleAnswers) {
  const World world;
  const UncertaintyBand askEveryCollision{0, std::numeric_limits<double>::infinity()};
  for (const UncertaintyBand band : {world.calibrate(5000, 13).band, askEveryCollision}) {
    for (std::uint64_t seed = 0; seed < 60; ++seed) {
      const Configurations q = test::uniformPoints(1 + seed % 40, kDim, 100 + seed);
      const HybridChecker single(world.model, world.exact, band);
      std::uint64_t before = world.exact->callCount();
      std::size_t expected = static_cast<std::size_t>(q.rows());
      for (Eigen::Index i = 0; i < q.rows(); ++i) {
        if (single.inCollision({q.row(i).data(), kDim})) {
          expected = static_cast<std::size_t>(i);
          break;
        }
      }
      const std::uint64_t singleCalls = world.exact->callCount() - before;
      const HybridChecker batch(world.model, world.exact, band);
      before = world.exact->callCount();
      EXPECT_EQ(batch.firstInCollision(q.data(), static_cast<std::size_t>(q.rows())), expected)
          << "seed " << seed;
      EXPECT_EQ(world.exact->callCount() - before, singleCalls) << "seed " << seed;
      EXPECT_EQ(batch.exactAnswers(), single.exactAnswers()) << "seed " << seed;
      EXPECT_EQ(batch.modelAnswers(), single.modelAnswers()) << "seed " << seed;
    }
  }
  const HybridChecker hybrid(world.model, world.exact, askEveryCollision);
  const double bad[2 * kDim] = {0, 0, 0, 0, NAN, 0};
  EXPECT_THROW(hybrid.firstInCollision(bad, 2), InvalidArgument);
}

// A hybrid whose exact checker is itself a hybrid (of the same model, asking the balls) gives,
// for a run, the answer of its configurations one by one: the inner one's run of questions must
// not disturb the outer one's.
TEST(HybridChecker, AHybridOfAHybridAnswersAsOneByOne) {
  const World world;
  const UncertaintyBand band = world.calibrate(5000, 17).band;
  const auto inner = std::make_shared<const HybridChecker>(
      world.model, world.exact, UncertaintyBand{0, std::numeric_limits<double>::infinity()});
  const HybridChecker outer(world.model, inner, band);
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const Configurations q = test::uniformPoints(1 + seed % 40, kDim, 300 + seed);
    std::size_t expected = static_cast<std::size_t>(q.rows());
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      if (outer.inCollision({q.row(i).data(), kDim})) {
        expected = static_cast<std::size_t>(i);
        break;
      }
    }
    EXPECT_EQ(outer.firstInCollision(q.data(), static_cast<std::size_t>(q.rows())), expected)
        << "seed " << seed;
  }
}

TEST(HybridChecker, RefusesBadArguments) {
  const World world;
  EXPECT_THROW(HybridChecker(nullptr, world.exact, {}), InvalidArgument);
  EXPECT_THROW(HybridChecker(world.model, nullptr, {}), InvalidArgument);
  const auto twoJoints =
      std::make_shared<FunctionChecker>("two", 2, [](const double*) { return false; });
  EXPECT_THROW(HybridChecker(world.model, twoJoints, {}), InvalidArgument);
  EXPECT_THROW(HybridChecker(world.model, world.exact, {0.5, 1}), InvalidArgument);
  EXPECT_THROW(HybridChecker(world.model, world.exact, {-1, -0.5}), InvalidArgument);
}

}  // namespace
}  // namespace fastron
