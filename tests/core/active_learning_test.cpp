// Algorithm 2: sample counts, bounds, exploitation near support points, random support choice.

#include "fastron/core/active_learning.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "fastron/core/error.h"
#include "test_worlds.h"

namespace fastron {
namespace {

Model modelWithSupport(const Eigen::MatrixXd& points, double gamma = 10) {
  const auto d = static_cast<std::size_t>(points.cols());
  return {FeatureMap::jointScaling(JointLimits::unitBox(d)),
          {KernelType::RationalQuadratic, gamma},
          Configurations(points),
          Eigen::VectorXd::Ones(points.rows())};
}

// Index of the nearest support point and its distance.
std::pair<Eigen::Index, double> nearest(const Eigen::MatrixXd& support,
                                        const Eigen::RowVectorXd& x) {
  Eigen::Index best = 0;
  const double d2 = (support.rowwise() - x).rowwise().squaredNorm().minCoeff(&best);
  return {best, std::sqrt(d2)};
}

TEST(ActiveLearning, ReturnsAMaxSamplesWithinTheJointLimits) {
  const Eigen::MatrixXd support = Configurations(test::uniformPoints(40, 3, 1));
  const JointLimits limits(Eigen::Vector3d(-3, 0, 1), Eigen::Vector3d(3, 1, 2));
  const Model model = *jointSpaceModel(limits, Kernel{}, support, Eigen::VectorXd::Ones(40));
  Rng rng(2);
  const Configurations q = activeLearning(model, {500, 5, 0.5}, rng);
  ASSERT_EQ(q.rows(), 500);
  ASSERT_EQ(q.cols(), 3);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    for (Eigen::Index j = 0; j < 3; ++j) {
      EXPECT_GE(q(i, j), limits.lower()[j] - 1e-12);
      EXPECT_LE(q(i, j), limits.upper()[j] + 1e-12);
    }
  }
}

TEST(ActiveLearning, ExploitsNearSupportPointsThenExplores) {
  // 10 support points, kappa = 3: 30 exploitation samples with a tiny variance, 70 uniform.
  const Eigen::MatrixXd support = Configurations(test::uniformPoints(10, 4, 3)) * 0.5;
  const Model model = modelWithSupport(support);
  Rng rng(4);
  const Configurations x = activeLearning(model, {100, 3, 1e-6}, rng);
  ASSERT_EQ(x.rows(), 100);
  std::vector<int> perSupport(10, 0);
  for (Eigen::Index i = 0; i < 30; ++i) {
    const auto [index, distance] = nearest(support, x.row(i));
    EXPECT_LT(distance, 0.01);
    ++perSupport[static_cast<std::size_t>(index)];
  }
  for (const int count : perSupport) EXPECT_EQ(count, 3);
  std::size_t far = 0;
  for (Eigen::Index i = 30; i < 100; ++i) far += nearest(support, x.row(i)).second > 0.05;
  EXPECT_GT(far, 60u);  // exploration is uniform, not near the support set
}

TEST(ActiveLearning, ExploitationShareCapsTheSamplesAroundSupportPoints) {
  // 40 support points, kappa 3 would give 120 near them; a share of 0.2 of 100 allows 20, at
  // most one per support point, and the other 80 are uniform.
  const Eigen::MatrixXd support = Configurations(test::uniformPoints(40, 4, 5)) * 0.5;
  const Model model = modelWithSupport(support);
  Rng rng(6);
  ActiveLearningParams params{100, 3, 1e-6};
  params.exploitationShare = 0.2;
  const Configurations x = activeLearning(model, params, rng);
  ASSERT_EQ(x.rows(), 100);
  std::set<Eigen::Index> visited;
  for (Eigen::Index i = 0; i < 20; ++i) {
    const auto [index, distance] = nearest(support, x.row(i));
    EXPECT_LT(distance, 0.01);
    visited.insert(index);
  }
  EXPECT_EQ(visited.size(), 20u);  // a random subset, each once
  std::size_t far = 0;
  for (Eigen::Index i = 20; i < 100; ++i) far += nearest(support, x.row(i)).second > 0.05;
  EXPECT_GT(far, 70u);
  params.exploitationShare = 0;
  const Configurations none = activeLearning(model, params, rng);
  far = 0;
  for (Eigen::Index i = 0; i < 100; ++i) far += nearest(support, none.row(i)).second > 0.05;
  EXPECT_GT(far, 90u);
}

TEST(ActiveLearning, DefaultVarianceIsOneOverTwoGamma) {
  const Eigen::MatrixXd support = Eigen::MatrixXd::Zero(1, 2);
  const double gamma = 50;
  const Model model = modelWithSupport(support, gamma);
  Rng rng(5);
  const Configurations x = activeLearning(model, {20000, 20000, 0}, rng);
  const double variance = x.array().square().mean();
  EXPECT_NEAR(variance, 1 / (2 * gamma), 0.0005);
}

TEST(ActiveLearning, ChoosesSupportPointsAtRandomWhenOverAllowance) {
  // kappa |S| = 200 > A_max = 50: the samples must not all come from the first 50 points.
  const Eigen::MatrixXd support = Configurations(test::uniformPoints(200, 2, 6)) * 0.9;
  const Model model = modelWithSupport(support, 1e4);
  Rng rng(7);
  const Configurations x = activeLearning(model, {50, 1, 1e-8}, rng);
  ASSERT_EQ(x.rows(), 50);
  std::size_t beyondFirst50 = 0;
  std::set<Eigen::Index> used;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const auto [index, distance] = nearest(support, x.row(i));
    EXPECT_LT(distance, 1e-3);
    beyondFirst50 += index >= 50;
    used.insert(index);
  }
  EXPECT_EQ(used.size(), 50u);  // one sample per chosen support point
  EXPECT_GT(beyondFirst50, 20u);
}

TEST(ActiveLearning, ClampsExploitationSamplesToTheInputBox) {
  const Eigen::MatrixXd support = Eigen::MatrixXd::Constant(1, 2, 1.0);  // a corner
  const Model model = modelWithSupport(support);
  Rng rng(8);
  const Configurations x = activeLearning(model, {1000, 1000, 0.5}, rng);
  EXPECT_LE(x.maxCoeff(), 1.0);
  EXPECT_GE(x.minCoeff(), -1.0);
  EXPECT_GT((x.array() == 1.0).count(), 500);  // many samples fell outside and were clamped
}

TEST(ActiveLearning, WithoutSupportPointsEverythingIsExploration) {
  const Model model(FeatureMap::jointScaling(JointLimits::unitBox(3)), Kernel{},
                    Configurations(0, 3), Eigen::VectorXd(0));
  Rng rng(9);
  EXPECT_EQ(activeLearning(model, {123, 5, 0}, rng).rows(), 123);
}

TEST(ActiveLearning, SameSeedSameSamples) {
  const Model model = modelWithSupport(Configurations(test::uniformPoints(30, 3, 10)));
  Rng a(11), b(11);
  EXPECT_EQ(activeLearning(model, {100, 2, 0}, a), activeLearning(model, {100, 2, 0}, b));
}

TEST(ActiveLearning, RejectsANegativeVariance) {
  const Model model = modelWithSupport(Eigen::MatrixXd::Zero(1, 2));
  Rng rng(12);
  EXPECT_THROW(activeLearning(model, {10, 1, -1}, rng), InvalidArgument);
  ActiveLearningParams share{10, 1, 0};
  share.exploitationShare = 1.5;
  EXPECT_THROW(activeLearning(model, share, rng), InvalidArgument);
  share.exploitationShare = std::nan("");
  EXPECT_THROW(activeLearning(model, share, rng), InvalidArgument);
}

}  // namespace
}  // namespace fastron
