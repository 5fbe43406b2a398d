// The paper's baselines on small analytic data: each separates what it should, SSVM's QP solution
// meets its KKT conditions, and the incremental SVM equals a batch solve of the same data.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fastron/baselines/box_qp.h"
#include "fastron/baselines/fastron_classifier.h"
#include "fastron/baselines/incremental_svm.h"
#include "fastron/baselines/libsvm_classifier.h"
#include "fastron/baselines/original_fastron_query.h"
#include "fastron/baselines/sparse_svm.h"
#include "fastron/core/error.h"
#include "test_worlds.h"

namespace fastron {
namespace {

double accuracy(const Classifier& c, const Configurations& q, const Labels& y) {
  std::size_t right = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    right += c.predict(q.row(i).data()) == (y[static_cast<std::size_t>(i)] > 0);
  return static_cast<double>(right) / static_cast<double>(q.rows());
}

// Two balls in [-1, 1]^2: a C-space with two obstacles.
struct TwoBalls {
  test::BallWorld world{{Eigen::Vector2d(-0.4, 0.3), Eigen::Vector2d(0.5, -0.4)}, 0.35};
  Configurations train = test::uniformPoints(400, 2, 1);
  Labels trainLabels = world.label(train);
  Configurations test = test::uniformPoints(3000, 2, 2);
  Labels testLabels = world.label(test);
};

TEST(Baselines, EveryClassifierSeparatesTwoBalls) {
  const TwoBalls data;
  const JointLimits limits = JointLimits::unitBox(2);
  FastronClassifier fastron(
      limits, {.kernel = {KernelType::RationalQuadratic, 30}, .maxIterations = 100000});
  IsvmClassifier isvm(limits, {KernelType::Gaussian, 30}, {.C = 10});
  SsvmClassifier ssvm(limits, {KernelType::RationalQuadratic, 30}, {.C = 10});
  LibsvmClassifier libsvm(limits, 30, 10);
  for (Classifier* c : std::initializer_list<Classifier*>{&fastron, &isvm, &ssvm, &libsvm}) {
    c->train(data.train, data.trainLabels);
    EXPECT_GT(accuracy(*c, data.test, data.testLabels), 0.93) << c->name();
    EXPECT_GT(accuracy(*c, data.train, data.trainLabels), 0.97) << c->name();
    EXPECT_GT(c->supportCount(), 3u) << c->name();
    EXPECT_LT(c->supportCount(), 400u) << c->name();
  }
  // SSVM minimises the number of support points: sparser than the plain SVM.
  EXPECT_LT(ssvm.supportCount(), libsvm.supportCount());
}

TEST(IncrementalSvm, EqualsABatchSolveOfTheSameData) {
  const TwoBalls data;
  const JointLimits limits = JointLimits::unitBox(2);
  IsvmClassifier isvm(limits, {KernelType::Gaussian, 20}, {.C = 5});
  isvm.train(data.train, data.trainLabels);
  EXPECT_LT(isvm.svm().maxKktViolation(), 1e-6);
  LibsvmClassifier batch(limits, 20, 5, 1e-7);
  batch.train(data.train, data.trainLabels);
  double worst = 0;
  for (Eigen::Index i = 0; i < data.test.rows(); ++i) {
    worst = std::max(worst, std::abs(isvm.score(data.test.row(i).data()) -
                                     batch.score(data.test.row(i).data())));
  }
  EXPECT_LT(worst, 1e-3) << "largest difference of the decision values";
  EXPECT_EQ(isvm.supportCount(), batch.supportCount());
}

TEST(IncrementalSvm, KeepsTheKktConditionsAfterEveryPoint) {
  IncrementalSvm svm({KernelType::Gaussian, 10}, 2);
  const Configurations q = test::uniformPoints(150, 3, 3);
  const Labels y = test::randomLabels(150, 4);  // overlapping classes: error vectors appear
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    svm.add({q.row(i).data(), 3}, y[static_cast<std::size_t>(i)]);
    ASSERT_LT(svm.maxKktViolation(), 1e-6) << "after point " << i;
  }
  std::size_t atBound = 0;
  for (const double a : svm.alphas()) atBound += a >= 2 - 1e-12;
  EXPECT_GT(atBound, 0u);
  EXPECT_THROW(svm.add(std::vector<double>{0, 0}, 1), InvalidArgument);
  EXPECT_THROW(svm.add(std::vector<double>{0, 0, 0}, 0), InvalidArgument);
}

TEST(IncrementalSvm, ActiveLearningFollowsAlgorithm3) {
  const TwoBalls data;
  IsvmActiveLearningParams params{.C = 10, .initialPoints = 50, .maxAdded = 350, .batch = 50};
  IsvmClassifier isvm(JointLimits::unitBox(2), {KernelType::Gaussian, 30}, params);
  std::size_t calls = 0;
  const std::size_t labelled = isvm.trainActively([&](const Configurations& q) {
    calls += static_cast<std::size_t>(q.rows());
    return data.world.label(q);
  });
  EXPECT_EQ(labelled, calls);
  EXPECT_LE(labelled, 400u);
  EXPECT_GE(labelled, 100u);
  EXPECT_LT(isvm.svm().maxKktViolation(), 1e-5);
  EXPECT_GT(accuracy(isvm, data.test, data.testLabels), 0.9);
}

TEST(SparseSvm, QpSolutionMeetsItsKktConditions) {
  // Random box QPs, rank-deficient (B 30 x 60) and full-rank (B 80 x 60): both solver paths.
  Rng rng(5);
  std::normal_distribution<double> normal;
  for (const Eigen::Index rows : {30, 80}) {
    Eigen::MatrixXd B(rows, 60);
    for (auto& v : B.reshaped()) v = normal(rng);
    const Eigen::VectorXd c = Eigen::VectorXd::Ones(60) * 3;
    const double upper = 0.5, tolerance = 1e-8;
    const BoxQpResult r = solveBoxQp(B, c, upper, tolerance);
    ASSERT_TRUE(r.converged) << rows << " rows";
    // KKT: stationarity, primal and dual feasibility, complementarity.
    const Eigen::VectorXd stationarity = B.transpose() * (B * r.x) - c - r.lowerDual + r.upperDual;
    EXPECT_LT(stationarity.cwiseAbs().maxCoeff(), 1e-7);
    EXPECT_GE(r.x.minCoeff(), 0.0);
    EXPECT_LE(r.x.maxCoeff(), upper);
    EXPECT_GE(r.lowerDual.minCoeff(), 0.0);
    EXPECT_GE(r.upperDual.minCoeff(), 0.0);
    EXPECT_LT(r.x.cwiseProduct(r.lowerDual).maxCoeff(), 1e-7);
    EXPECT_LT((Eigen::VectorXd::Constant(60, upper) - r.x).cwiseProduct(r.upperDual).maxCoeff(),
              1e-7);
    // And so no feasible point does better.
    auto objective = [&](const Eigen::VectorXd& x) {
      return 0.5 * (B * x).squaredNorm() - c.dot(x);
    };
    for (int trial = 0; trial < 200; ++trial) {
      Eigen::VectorXd other = r.x;
      for (auto& v : other) v = std::clamp(v + 0.05 * normal(rng), 0.0, upper);
      EXPECT_GE(objective(other), objective(r.x) - 1e-6);
    }
  }
  // SSVM's own QPs, every iteration.
  const TwoBalls data;
  SsvmClassifier ssvm(JointLimits::unitBox(2), {KernelType::RationalQuadratic, 30},
                      {.C = 10, .qpTolerance = 1e-6});
  ssvm.train(data.train, data.trainLabels);
  EXPECT_TRUE(ssvm.report().qpConverged);
  EXPECT_LT(ssvm.report().qpStationarity, 1e-6);
  EXPECT_LT(ssvm.report().qpComplementarity, 1e-6);
  EXPECT_GE(ssvm.report().iterations, 3u);
}

TEST(Baselines, RefuseBadInput) {
  EXPECT_THROW(IncrementalSvm({KernelType::Gaussian, 1}, 0), InvalidArgument);
  EXPECT_THROW(LibsvmClassifier(JointLimits::unitBox(2), -1, 1), InvalidArgument);
  SsvmClassifier ssvm(JointLimits::unitBox(2), {KernelType::RationalQuadratic, 10});
  EXPECT_THROW(ssvm.train(Configurations(2, 2), Labels{1}), InvalidArgument);
  EXPECT_THROW(solveBoxQp(Eigen::MatrixXd::Identity(2, 2), Eigen::VectorXd::Ones(3), 1, 1e-6),
               InvalidArgument);
}

// The original Fastron's query is the paper's kernel scaled by (gamma / 2)^2: the same sign as
// the model's score wherever the score is not within float rounding of 0, for the dimensions
// the original unrolls (4 to 7) and one it sums column by column (2, 9).
TEST(OriginalFastronQuery, ScoresTheModelsSumScaledByTheKernelWidth) {
  for (const std::size_t d : {2, 4, 5, 6, 7, 9}) {
    SCOPED_TRACE("d " + std::to_string(d));
    const Configurations support = test::uniformPoints(300, d, 5);
    std::mt19937_64 random(d);
    std::normal_distribution<double> normal;
    Eigen::VectorXd weights(support.rows());
    for (Eigen::Index i = 0; i < weights.size(); ++i) weights[i] = normal(random);
    const double gamma = 3.0;
    const Model model(FeatureMap::jointScaling(JointLimits::unitBox(d)),
                      {KernelType::RationalQuadratic, gamma}, support, weights);
    const OriginalFastronQuery original(model);
    const Configurations q = test::uniformPoints(500, d, 6);
    const double scale = (gamma / 2) * (gamma / 2);
    std::size_t compared = 0;
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      const double exact = model.scoreExact(q.row(i).data());
      Eigen::VectorXd x(static_cast<Eigen::Index>(model.featureDim()));
      model.features().map(q.row(i).data(), x.data());
      EXPECT_NEAR(original.scoreFeatures(x.data()), scale * exact,
                  1e-9 * scale * weights.cwiseAbs().sum());
      if (std::abs(exact) < 1e-6) continue;
      EXPECT_EQ(original.inCollision(q.row(i).data()), model.inCollision(q.row(i).data()));
      ++compared;
    }
    EXPECT_GT(compared, 450U);
  }
}

TEST(OriginalFastronQuery, RefusesAKernelTheOriginalDoesNotHave) {
  const Configurations support = test::uniformPoints(10, 6, 5);
  const Eigen::VectorXd weights = Eigen::VectorXd::Ones(10);
  const FeatureMap features = FeatureMap::jointScaling(JointLimits::unitBox(6));
  EXPECT_THROW(OriginalFastronQuery(Model(features, {KernelType::Gaussian, 3}, support, weights)),
               InvalidArgument);
  Kernel points{KernelType::RationalQuadratic, 3};
  points.block = 3;
  EXPECT_THROW(OriginalFastronQuery(Model(features, points, support, weights)), InvalidArgument);
}

}  // namespace
}  // namespace fastron
