// Algorithm 1: convergence (Claim 1), support cap, revert safeguard, F = K alpha (within the float
// columns' bound), Gram columns only where weights change.

#include "fastron/core/trainer.h"

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/gram_columns.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/reference_trainer.h"
#include "fastron/core/simd.h"
#include "simd_path_guard.h"
#include "temp_dir.h"
#include "test_worlds.h"

namespace fastron {
namespace {

Eigen::MatrixXd fullGram(const Eigen::MatrixXd& x, const Kernel& kernel) {
  const auto d = static_cast<std::size_t>(x.cols());
  Eigen::MatrixXd k(x.rows(), x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    for (Eigen::Index j = 0; j < x.rows(); ++j) {
      const auto xi = [&](std::size_t c) { return x(i, static_cast<Eigen::Index>(c)); };
      const auto xj = [&](std::size_t c) { return x(j, static_cast<Eigen::Index>(c)); };
      k(i, j) = kernel.between<double>(xi, xj, d);
    }
  }
  return k;
}

double hypothesisError(const Trainer& trainer) {
  if (trainer.size() == 0) return 0;
  const Eigen::VectorXd kAlpha =
      fullGram(trainer.points(), trainer.params().kernel) * trainer.weights();
  return (kAlpha - trainer.hypothesis()).cwiseAbs().maxCoeff();
}

// Claim 1 is about every training point, also those discarded as non-support points: check the
// margins of the original set with the final model.
std::size_t nonPositiveMargins(const Model& model, const Configurations& q, const Labels& y) {
  std::size_t count = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    count += y[static_cast<std::size_t>(i)] * model.scoreExact(q.row(i).data()) <= 0;
  }
  return count;
}

TrainParams uncapped(double gamma, double beta = 1, std::uint32_t block = 0,
                     double wholeShare = 0) {
  TrainParams p;
  p.kernel.gamma = gamma;
  p.kernel.block = block;
  p.kernel.wholeShare = wholeShare;
  p.beta = beta;
  p.maxIterations = 10'000'000;
  p.maxSupportPoints = 1'000'000;
  p.maxWeightOverBeta = std::numeric_limits<double>::infinity();
  return p;
}

struct ConvergenceCase {
  std::size_t dim, n;
  double gamma, beta;
  bool randomLabels;
  std::uint32_t block = 0;  ///< point terms of the kernel (Kernel::block)
  double wholeShare = 0;
};

class Convergence : public ::testing::TestWithParam<ConvergenceCase> {};

TEST_P(Convergence, EveryTrainingPointEndsWithPositiveMargin) {
  const auto c = GetParam();
  const Configurations q = test::uniformPoints(c.n, c.dim, 7);
  const Labels y = c.randomLabels
                       ? test::randomLabels(c.n, 8)
                       : test::BallWorld::random(c.dim, 4, 0.3 * std::sqrt(c.dim), 9).label(q);
  Trainer trainer(JointLimits::unitBox(c.dim), uncapped(c.gamma, c.beta, c.block, c.wholeShare));
  trainer.addPoints(q, y);
  const UpdateReport report = trainer.update();

  EXPECT_EQ(report.stopReason, StopReason::Converged);
  EXPECT_EQ(report.misclassified, 0u);
  EXPECT_FALSE(report.reverted);
  EXPECT_GT(report.supportCount, 20u) << "too easy a dataset to say anything";
  EXPECT_EQ(nonPositiveMargins(*trainer.model(), q, y), 0u);
  EXPECT_LE(hypothesisError(trainer), trainer.hypothesisErrorBound() + 1e-9);
  // Only support points survive sparsification.
  EXPECT_EQ(trainer.size(), report.supportCount);
  EXPECT_EQ(trainer.model()->supportCount(), report.supportCount);
  EXPECT_TRUE((trainer.weights().array() != 0).all());
}

INSTANTIATE_TEST_SUITE_P(Claim1, Convergence,
                         ::testing::Values(ConvergenceCase{2, 400, 60, 1, true},
                                           ConvergenceCase{4, 400, 20, 1, true},
                                           ConvergenceCase{2, 2000, 30, 1, false},
                                           ConvergenceCase{4, 4000, 10, 1, false},
                                           ConvergenceCase{4, 2000, 10, 50, false},
                                           ConvergenceCase{7, 1000, 5, 500, true},
                                           ConvergenceCase{6, 2000, 20, 10, false, 3, 0.2},
                                           ConvergenceCase{12, 1000, 10, 1, true, 3, 0}),
                         [](const auto& info) {
                           const auto& c = info.param;
                           return std::to_string(c.dim) + "d_n" + std::to_string(c.n) + "_beta" +
                                  std::to_string(static_cast<int>(c.beta)) +
                                  (c.randomLabels ? "_randomLabels" : "_balls") +
                                  (c.block ? "_pointTerms" : "");
                         });

TEST(Trainer, ConditionalBiasWeighsCollisionPointsMore) {
  const Configurations q = test::uniformPoints(2000, 2, 3);
  const Labels y = test::BallWorld::random(2, 4, 0.35, 4).label(q);
  const Configurations probe = test::uniformPoints(20000, 2, 5);
  auto positives = [&](double beta) {
    Trainer trainer(JointLimits::unitBox(2), uncapped(30, beta));
    trainer.addPoints(q, y);
    trainer.update();
    const Eigen::VectorXd s = trainer.model()->scoreBatch(probe);
    return (s.array() > 0).count();
  };
  // A larger beta pads the C-space obstacles: more of the space is predicted in collision.
  EXPECT_GT(positives(100), positives(1));
}

TEST(Trainer, ForgottenWeightsRetrainLikeAFreshTrainer) {
  // After forgetWeights, an update is Algorithm 1 from scratch on the points the trainer holds.
  const test::BallWorld world = test::BallWorld::random(3, 5, 0.3, 11);
  const Configurations first = test::uniformPoints(800, 3, 12);
  const Configurations second = test::uniformPoints(400, 3, 13);
  Trainer trainer(JointLimits::unitBox(3), uncapped(20, 5));
  trainer.addPoints(first, world.label(first));
  trainer.update();
  trainer.addPoints(second, world.label(second));
  trainer.forgetWeights();
  EXPECT_EQ(trainer.supportCount(), 0u);
  EXPECT_TRUE(trainer.hypothesis().isZero());
  const Configurations held = trainer.configurations();
  Labels labels;
  for (const double y : trainer.labels()) labels.push_back(y > 0 ? 1 : -1);
  trainer.update();

  Trainer fresh(JointLimits::unitBox(3), uncapped(20, 5));
  fresh.addPoints(held, labels);
  fresh.update();
  EXPECT_EQ(trainer.configurations(), fresh.configurations());
  EXPECT_EQ(trainer.weights(), fresh.weights());
}

TEST(Trainer, SceneDefaultsChangeOnlyTaskSpaceObstacleModels) {
  // One scene learned at once from uniform samples: a larger beta and a narrower kernel for
  // task-space obstacle models, point terms alone (a point field answers them); self-collision
  // and joint-space models keep the defaults.
  const TrainParams fk = defaultTrainParams(FeatureKind::Kinematic);
  const TrainParams scene = sceneTrainParams(FeatureKind::Kinematic);
  EXPECT_GT(scene.beta, fk.beta);
  EXPECT_GT(scene.kernel.gamma, fk.kernel.gamma);
  EXPECT_EQ(scene.kernel.block, fk.kernel.block);
  EXPECT_EQ(scene.kernel.wholeShare, 0.0);
  EXPECT_GT(fk.kernel.wholeShare, 0.0);
  // Up to 64000 samples learned at once: room for the iterations and support points they need.
  EXPECT_EQ(scene.maxIterations, 20000u);
  EXPECT_EQ(scene.maxSupportPoints, 5000u);
  for (const auto& [kind, self] :
       {std::pair{FeatureKind::Kinematic, true}, std::pair{FeatureKind::JointScaling, false}}) {
    EXPECT_EQ(sceneTrainParams(kind, self).beta, defaultTrainParams(kind, self).beta);
    EXPECT_EQ(sceneTrainParams(kind, self).kernel.gamma,
              defaultTrainParams(kind, self).kernel.gamma);
  }
}

TEST(Trainer, SupportCapIsRespected) {
  const Configurations q = test::uniformPoints(1000, 2, 11);
  const Labels y = test::randomLabels(1000, 12);
  TrainParams p = uncapped(60);
  p.maxSupportPoints = 25;
  Trainer trainer(JointLimits::unitBox(2), p);
  trainer.addPoints(q, y);
  const UpdateReport report = trainer.update();
  EXPECT_EQ(report.stopReason, StopReason::SupportCap);
  EXPECT_LE(report.supportCount, 25u);
  EXPECT_LE(trainer.model()->supportCount(), 25u);
  EXPECT_GT(report.misclassified, 0u);
  EXPECT_LE(hypothesisError(trainer), trainer.hypothesisErrorBound() + 1e-9);
}

TEST(Trainer, WeightLimitStopsTheGrowthOfNearlyCoincidentOppositePoints) {
  // Two points 0.0003 apart with opposite labels: positive margins for both need weights of
  // about 1 / (1 - k) = 1 / (gamma d^2) = 1.1e6.
  Configurations q(3, 2);
  q << 0.5, 0.5, 0.5003, 0.5, -0.5, -0.5;
  const Labels y{1, -1, -1};
  const auto trained = [&](double maxWeightOverBeta) {
    TrainParams p = uncapped(10);
    p.maxWeightOverBeta = maxWeightOverBeta;
    auto trainer = std::make_unique<Trainer>(JointLimits::unitBox(2), p);
    trainer->addPoints(q, y);
    const UpdateReport report = trainer->update();
    return std::pair{report, trainer->weights().cwiseAbs().maxCoeff()};
  };
  const auto [unlimited, unlimitedWeight] = trained(std::numeric_limits<double>::infinity());
  EXPECT_EQ(unlimited.stopReason, StopReason::Converged);
  EXPECT_GT(unlimitedWeight, 1e5);

  const auto [limited, limitedWeight] = trained(TrainParams{}.maxWeightOverBeta);
  EXPECT_EQ(limited.stopReason, StopReason::WeightLimit);
  EXPECT_LE(limitedWeight, 1e5);
  EXPECT_GT(limited.misclassified, 0u);
  EXPECT_EQ(toString(limited.stopReason), "weight limit");
}

TEST(Trainer, IterationLimitStopsTraining) {
  const Configurations q = test::uniformPoints(500, 2, 13);
  TrainParams p = uncapped(60);
  p.maxIterations = 10;
  Trainer trainer(JointLimits::unitBox(2), p);
  trainer.addPoints(q, test::randomLabels(500, 14));
  const UpdateReport report = trainer.update();
  EXPECT_EQ(report.stopReason, StopReason::IterationLimit);
  EXPECT_EQ(report.iterations, 10u);
  EXPECT_LE(report.supportCount, 10u);
}

// The safeguard of Algorithm 1, line 21: when the iteration limit interrupts the repair that
// follows a redundant-point removal, the solution from before the removal comes back.
TEST(Trainer, RevertSafeguardRestoresTheBetterSolution) {
  const Configurations q = test::uniformPoints(300, 2, 21);
  const Labels y = test::BallWorld::random(2, 3, 0.45, 22).label(q);
  std::size_t reverts = 0;
  for (std::size_t limit = 1; limit < 400; ++limit) {
    TrainParams p = uncapped(20);
    p.maxIterations = limit;
    Trainer trainer(JointLimits::unitBox(2), p);
    trainer.addPoints(q, y);
    const UpdateReport report = trainer.update();
    if (!report.reverted) continue;
    ++reverts;
    EXPECT_LT(report.misclassified, report.misclassifiedBeforeRevert) << "limit " << limit;
    EXPECT_EQ(report.stopReason, StopReason::IterationLimit);
    EXPECT_LE(hypothesisError(trainer), trainer.hypothesisErrorBound() + 1e-9);
    EXPECT_EQ(report.supportCount,
              static_cast<std::size_t>((trainer.weights().array() != 0).count()));
  }
  EXPECT_GT(reverts, 0u) << "no iteration limit triggered the safeguard; the test proves nothing";
}

TEST(Trainer, HypothesisEqualsGramTimesWeightsThroughAnyHistory) {
  const std::size_t d = 3;
  test::BallWorld world = test::BallWorld::random(d, 3, 0.5, 31);
  TrainParams p = uncapped(10, 20);
  Trainer trainer(JointLimits::unitBox(d), p);
  const Configurations q = test::uniformPoints(800, d, 32);
  trainer.addPoints(q, world.label(q));
  EXPECT_LT(hypothesisError(trainer), 1e-12);  // all weights zero
  Rng rng(33);
  for (int round = 0; round < 6; ++round) {
    trainer.update();
    EXPECT_LE(hypothesisError(trainer), trainer.hypothesisErrorBound() + 1e-9)
        << "after update, round " << round;
    world.move(0.05);
    trainer.relabel(world.label(Configurations(trainer.points())));
    EXPECT_LE(hypothesisError(trainer), trainer.hypothesisErrorBound() + 1e-9)
        << "after relabel, round " << round;
    const Configurations fresh = activeLearning(*trainer.model(), {200, 3, 0}, rng);
    trainer.addPoints(fresh, world.label(fresh));
    EXPECT_LE(hypothesisError(trainer), trainer.hypothesisErrorBound() + 1e-9)
        << "after adding points, round " << round;
  }
}

// F of new points (addSums of gram_columns_impl.h) for every kernel form and SIMD path, the row
// count not a multiple of a register: equal to the Gram matrix times the weights, and the same
// whether the rows go in one chunk or in chunks run out of order on other threads.
TEST(Trainer, NewPointsGetTheHypothesisOfTheCurrentWeightsInAnyChunks) {
  const std::size_t d = 6;
  test::BallWorld world = test::BallWorld::random(d, 3, 0.6, 41);
  const Configurations first = test::uniformPoints(600, d, 42);
  const Configurations fresh = test::uniformPoints(333, d, 43);
  const ChunkRunner backwardsOnThreads =
      [](std::size_t n, std::size_t chunk,
         const std::function<void(std::size_t, std::size_t)>& body) {
        std::vector<std::thread> threads;
        for (std::size_t begin = (n - 1) / chunk * chunk;; begin -= chunk) {
          threads.emplace_back(
              [&body, begin, n, chunk] { body(begin, std::min(n, begin + chunk)); });
          if (begin == 0) break;
        }
        for (std::thread& t : threads) t.join();
      };
  const test::SimdPathGuard guard;
  for (const SimdPath path : supportedSimdPaths()) {
    useSimdPath(path);
    for (const KernelType type : {KernelType::RationalQuadratic, KernelType::Gaussian}) {
      for (const std::uint32_t block : {0u, 3u}) {
        SCOPED_TRACE(std::string(toString(path)) +
                     (type == KernelType::Gaussian ? " Gaussian" : " RQ") + " block " +
                     std::to_string(block));
        TrainParams p = uncapped(20, 10, block, 0.3);
        p.kernel.type = type;
        Trainer serial(JointLimits::unitBox(d), p);
        serial.addPoints(first, world.label(first));
        serial.update();
        ASSERT_GT(serial.supportCount(), 20u);
        Trainer chunked = serial;
        serial.addPoints(fresh, world.label(fresh));
        chunked.addPoints(fresh, world.label(fresh), backwardsOnThreads);
        EXPECT_LE(hypothesisError(serial), serial.hypothesisErrorBound() + 1e-9);
        EXPECT_EQ(chunked.hypothesis(), serial.hypothesis());
      }
    }
  }
}

TEST(Trainer, RelabelZeroesSupportPointsWhoseLabelFlipped) {
  const Configurations q = test::uniformPoints(500, 2, 41);
  Trainer trainer(JointLimits::unitBox(2), uncapped(30));
  trainer.addPoints(q, test::BallWorld::random(2, 3, 0.4, 42).label(q));
  trainer.update();
  Labels flipped(trainer.size());
  for (std::size_t i = 0; i < flipped.size(); ++i) {
    flipped[i] = static_cast<std::int8_t>(trainer.labels()[static_cast<Eigen::Index>(i)]);
  }
  flipped[0] = static_cast<std::int8_t>(-flipped[0]);
  const std::size_t before = trainer.supportCount();
  trainer.relabel(flipped);
  EXPECT_EQ(trainer.weights()[0], 0.0);
  EXPECT_EQ(trainer.supportCount(), before - 1);
  EXPECT_LE(hypothesisError(trainer), trainer.hypothesisErrorBound() + 1e-9);
  const UpdateReport report = trainer.update();
  EXPECT_EQ(report.stopReason, StopReason::Converged);
}

TEST(Trainer, ComputesOneGramColumnPerWeightChange) {
  const std::size_t n = 4000;
  const Configurations q = test::uniformPoints(n, 2, 51);
  Trainer trainer(JointLimits::unitBox(2), uncapped(30));
  trainer.addPoints(q, test::BallWorld::random(2, 4, 0.3, 52).label(q));
  const UpdateReport first = trainer.update();
  // A column for each weight change, and none otherwise (the Gram matrix is never built).
  EXPECT_EQ(first.gramColumnsComputed, first.iterations);
  EXPECT_GE(first.gramColumnsComputed, first.supportCount);
  EXPECT_LE(hypothesisError(trainer), trainer.hypothesisErrorBound() + 1e-9);
  // A second update on unchanged data has nothing to do.
  const UpdateReport second = trainer.update();
  EXPECT_EQ(second.gramColumnsComputed, 0u);
  EXPECT_EQ(second.iterations, 0u);
  EXPECT_EQ(second.stopReason, StopReason::Converged);
}

// The optimised Algorithm 1 with double Gram columns against the plain scalar one
// (reference_trainer.h) on seeded data: the same iterations, stop reason, support set and
// weights, with and without the support cap. With float columns (the default), the guarantees.
struct ReferenceCase {
  std::size_t dim, n;
  double gamma, beta;
  std::size_t cap;
  std::uint32_t block = 0;  ///< point terms of the kernel (Kernel::block)
  double wholeShare = 0;
};

/// A case's seeded data, its settings (double columns) and the scalar reference trained on them.
struct ReferenceRun {
  Configurations q;
  Labels y;
  TrainParams params;
  ReferenceTraining reference;
};

ReferenceRun referenceRun(const ReferenceCase& c) {
  ReferenceRun run;
  run.q = test::uniformPoints(c.n, c.dim, 91);
  // Balls in at most 7 coordinates (features beyond them stand for task-space ones, which
  // depend on 7 joints; in 12 dimensions a ball world is all one class).
  const std::size_t ballDim = std::min<std::size_t>(c.dim, 7);
  run.y = test::BallWorld::random(ballDim, 4, 0.3 * std::sqrt(static_cast<double>(ballDim)), 92)
              .label(run.q.leftCols(static_cast<Eigen::Index>(ballDim)));
  run.params = uncapped(c.gamma, c.beta, c.block, c.wholeShare);
  run.params.maxSupportPoints = c.cap;
  run.params.floatGramColumns = false;
  // On the features as a Trainer stores them: rounded to float (trainer.cpp).
  const Eigen::MatrixXd features =
      FeatureMap::jointScaling(JointLimits::unitBox(c.dim)).map(run.q).cast<float>().cast<double>();
  run.reference = trainReference(features, run.y, run.params);
  return run;
}

class AgainstReference : public ::testing::TestWithParam<ReferenceCase> {};

TEST_P(AgainstReference, SameSupportSetAndWeights) {
  const auto c = GetParam();
  const auto [q, y, p, reference] = referenceRun(c);
  // Algorithm 1's passes run on the active SIMD path (gram_columns_impl.h): each must match.
  const test::SimdPathGuard guard;
  for (const SimdPath path : supportedSimdPaths()) {
    SCOPED_TRACE(toString(path));
    useSimdPath(path);
    Trainer trainer(JointLimits::unitBox(c.dim), p);
    trainer.addPoints(q, y);
    const UpdateReport report = trainer.update();
    EXPECT_EQ(report.iterations, reference.report.iterations);
    EXPECT_EQ(report.stopReason, reference.report.stopReason);
    EXPECT_EQ(report.reverted, reference.report.reverted);
    EXPECT_EQ(report.misclassified, reference.report.misclassified);
    ASSERT_EQ(report.supportCount, reference.report.supportCount);
    // The trainer keeps only its support points, in their original order.
    std::size_t k = 0;
    for (std::size_t i = 0; i < c.n; ++i) {
      if (reference.alpha[i] == 0) continue;
      ASSERT_LT(k, trainer.size());
      const auto row = static_cast<Eigen::Index>(k);
      EXPECT_EQ(trainer.configurations().row(row), q.row(static_cast<Eigen::Index>(i)));
      EXPECT_NEAR(trainer.weights()[row], reference.alpha[i], 1e-9 * std::max(1.0, c.beta));
      EXPECT_NEAR(trainer.hypothesis()[row], reference.f[i], 1e-9 * std::max(1.0, c.beta));
      ++k;
    }
    EXPECT_EQ(k, trainer.size());
    EXPECT_GE(report.iterations, std::min<std::size_t>(100, c.cap))
        << "the case must exercise Algorithm 1";
  }
}

// Float columns may choose differently where two margins are within their error of each other;
// the guarantees hold all the same: the reference's stop reason, Claim 1 on every training point
// (not only the support points kept) when converged, the cap, an exact misclassified count and F
// within its bound. The support set stays close to the reference's.
TEST_P(AgainstReference, FloatColumnsKeepItsGuarantees) {
  const auto c = GetParam();
  const auto [q, y, doubleColumns, reference] = referenceRun(c);
  TrainParams p = doubleColumns;
  p.floatGramColumns = true;
  const test::SimdPathGuard guard;
  for (const SimdPath path : supportedSimdPaths()) {
    SCOPED_TRACE(toString(path));
    useSimdPath(path);
    Trainer trainer(JointLimits::unitBox(c.dim), p);
    trainer.addPoints(q, y);
    const UpdateReport report = trainer.update();
    EXPECT_EQ(report.stopReason, reference.report.stopReason);
    EXPECT_LE(report.supportCount, c.cap);
    EXPECT_EQ(report.misclassified, nonPositiveMargins(*trainer.model(), q, y));
    EXPECT_LE(hypothesisError(trainer), trainer.hypothesisErrorBound() + 1e-9);
    EXPECT_GT(trainer.hypothesisErrorBound(), 0) << "the columns were not float";
    const auto near = [](std::size_t value, std::size_t of) {
      return std::abs(static_cast<double>(value) - static_cast<double>(of)) <=
             0.05 * static_cast<double>(of) + 2;
    };
    EXPECT_TRUE(near(report.supportCount, reference.report.supportCount))
        << report.supportCount << " support points against " << reference.report.supportCount;
    EXPECT_TRUE(near(report.iterations, reference.report.iterations))
        << report.iterations << " iterations against " << reference.report.iterations;
  }
}

// A float column's values lie within the bound the Trainer adds up for them (floatColumnError of
// gram_columns.h), against the double column of the same float features, at thousands of rows on
// every SIMD path and for rows that start anywhere (the value depends on its row alone). Points
// uniform in [-1, 1]^d are 2d/3 apart in r^2 on average: gamma 1.5 / d puts the typical pair at
// gamma r^2 / 2 = 1/2, where the kernel is most sensitive to its distance.
TEST(Trainer, FloatColumnValuesStayWithinTheirBound) {
  const std::size_t rows = 3001;
  const test::SimdPathGuard guard;
  // 12 features go a register of rows at a time, 15 and 27 a block of rows at a time.
  for (const std::size_t d : {12ul, 15ul, 27ul}) {
    const Eigen::MatrixXf xf = test::uniformPoints(rows, d, 61).cast<float>();  // column-major
    const Eigen::MatrixXd x = xf.cast<double>();
    for (const SimdPath path : supportedSimdPaths()) {
      useSimdPath(path);
      const detail::GramPasses& passes = detail::activeGramPasses();
      for (const std::uint32_t block : {0u, 3u}) {
        for (const double gamma : {1.5 / static_cast<double>(d), 40.0}) {
          SCOPED_TRACE(std::string(toString(path)) + " d " + std::to_string(d) + " block " +
                       std::to_string(block) + " gamma " + std::to_string(gamma));
          Kernel kernel{KernelType::RationalQuadratic, gamma, block, 0.5};
          const detail::GramKernel gram{kernel.type, gamma, block, kernel.wholeWeight(),
                                        kernel.pointWeight(d)};
          const double bound = detail::floatColumnError(gram, d);
          std::vector<double> exact(rows), inFloat(rows), shifted(rows);
          double worst = 0;
          for (const std::size_t i : {0ul, 17ul, 2999ul}) {
            passes.column(x.data(), xf.data(), rows, d, i, 0, rows, gram, exact.data());
            passes.columnInFloat(xf.data(), rows, d, i, 0, rows, gram, inFloat.data());
            passes.columnInFloat(xf.data(), rows, d, i, 5, rows, gram, shifted.data() + 5);
            for (std::size_t j = 0; j < rows; ++j) {
              worst = std::max(worst, std::abs(inFloat[j] - exact[j]));
              if (j >= 5) {
                ASSERT_EQ(shifted[j], inFloat[j]) << "row " << j;
              }
            }
          }
          EXPECT_GT(worst, 0) << "the float column equals the double one: not computed in float";
          EXPECT_LE(worst, bound);
          EXPECT_LT(bound, 1e-5);  // a bound of use: margins of training are far larger
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Seeded, AgainstReference,
    ::testing::Values(ReferenceCase{2, 1500, 30, 1, 100000}, ReferenceCase{7, 3000, 5, 500, 100000},
                      ReferenceCase{7, 3000, 5, 500, 60}, ReferenceCase{12, 2000, 3, 10, 100000},
                      // Point terms, on the register and feature paths.
                      ReferenceCase{12, 2000, 10, 10, 100000, 3, 0.2},
                      ReferenceCase{18, 1500, 10, 10, 100000, 3, 0}),
    [](const auto& info) {
      const ReferenceCase& c = info.param;
      return std::to_string(c.dim) + "d_beta" + std::to_string(static_cast<int>(c.beta)) +
             (c.cap < 100000 ? "_capped" : "") + (c.block ? "_pointTerms" : "");
    });

TEST(Trainer, ContradictoryDuplicatesEndAtTheIterationLimit) {
  Configurations q(2, 2);
  q << 0.1, 0.2, 0.1, 0.2;
  TrainParams p = uncapped(10);
  p.maxIterations = 50;
  Trainer trainer(JointLimits::unitBox(2), p);
  trainer.addPoints(q, Labels{1, -1});
  const UpdateReport report = trainer.update();
  EXPECT_EQ(report.stopReason, StopReason::IterationLimit);
  EXPECT_GE(report.misclassified, 1u);
}

TEST(Trainer, EmptyUpdateConvergesWithNoSupport) {
  Trainer trainer(JointLimits::unitBox(3), TrainParams{});
  const UpdateReport report = trainer.update();
  EXPECT_EQ(report.stopReason, StopReason::Converged);
  EXPECT_EQ(report.supportCount, 0u);
  EXPECT_EQ(trainer.model()->supportCount(), 0u);
  EXPECT_EQ(trainer.model()->score(std::vector<double>{0, 0, 0}), 0.0);
}

TEST(Trainer, JointLimitsScaleIntoInputSpace) {
  const JointLimits limits(Eigen::Vector2d(0, -2), Eigen::Vector2d(3.14, 2));
  Trainer trainer(limits, TrainParams{});
  Configurations q(2, 2);
  q << 0, -2, 3.14, 1;
  trainer.addPoints(q, Labels{1, -1});
  EXPECT_NEAR(trainer.points()(0, 0), -1, 1e-12);
  EXPECT_NEAR(trainer.points()(0, 1), -1, 1e-12);
  EXPECT_NEAR(trainer.points()(1, 0), 1, 1e-12);
  EXPECT_NEAR(trainer.points()(1, 1), 0.5, 1e-12);
}

TEST(Trainer, StoresFeaturesRoundedToFloatAsARebuiltModelDoes) {
  const Configurations q = test::uniformPoints(300, 3, 95);
  Trainer trainer(JointLimits(Eigen::Vector3d(-3, -2, -1), Eigen::Vector3d(3.1, 2.2, 1.3)),
                  uncapped(10, 1));
  trainer.addPoints(q, test::BallWorld::random(3, 3, 0.5, 96).label(q));
  trainer.update();
  EXPECT_EQ(trainer.points(), trainer.points().cast<float>().cast<double>());
  const auto trained = trainer.model();
  // A model rebuilt from its configurations (as a model file is loaded) has the same features, so
  // the same scores bit for bit.
  const Model rebuilt(trained->features(), trained->kernel(), trained->supportConfigurations(),
                      trained->weights());
  EXPECT_EQ(rebuilt.supportFeatures(), trained->supportFeatures());
  for (Eigen::Index i = 0; i < 20; ++i) {
    EXPECT_EQ(rebuilt.scoreExact(q.row(i).data()), trained->scoreExact(q.row(i).data()));
  }
}

TEST(Trainer, RejectsBadInput) {
  EXPECT_THROW(Trainer(JointLimits::unitBox(2), TrainParams{.beta = 0.5}), InvalidArgument);
  EXPECT_THROW(Trainer(JointLimits::unitBox(2), TrainParams{.kernel = {KernelType::Gaussian, -1}}),
               InvalidArgument);
  EXPECT_THROW(Trainer(JointLimits::unitBox(2), TrainParams{.maxSupportPoints = 0}),
               InvalidArgument);
  EXPECT_THROW(Trainer(JointLimits::unitBox(2), TrainParams{.maxWeightOverBeta = 0.5}),
               InvalidArgument);
  EXPECT_THROW(Trainer(JointLimits::unitBox(2), TrainParams{.maxWeightOverBeta = std::nan("")}),
               InvalidArgument);
  Trainer trainer(JointLimits::unitBox(2), TrainParams{});
  Configurations q(2, 2);
  q << 0, 0, 0.5, 0.5;
  EXPECT_THROW(trainer.addPoints(q, Labels{1}), InvalidArgument);
  EXPECT_THROW(trainer.addPoints(q, Labels{1, 0}), InvalidArgument);
  EXPECT_THROW(trainer.addPoints(Configurations::Zero(2, 3), Labels{1, -1}), InvalidArgument);
  q(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(trainer.addPoints(q, Labels{1, -1}), InvalidArgument);
  // Beyond float range: training and queries compute features in float.
  q(1, 1) = 1e31;
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] {
                trainer.addPoints(q, Labels{1, -1});
              }),
              ::testing::HasSubstr("at most 1e30 in magnitude"));
  EXPECT_EQ(trainer.size(), 0u);  // a refused call changes nothing
  EXPECT_THROW(trainer.relabel(Labels{1}), InvalidArgument);
}

}  // namespace
}  // namespace fastron
