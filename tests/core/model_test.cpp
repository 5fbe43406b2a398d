#include "fastron/core/model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fastron/core/error.h"
#include "fastron/core/trainer.h"
#include "test_worlds.h"

namespace fastron {
namespace {

std::shared_ptr<const Model> trainedModel(std::size_t dim, std::size_t n, KernelType type,
                                          double gamma, double beta, std::uint32_t block = 0,
                                          double wholeShare = 0) {
  return test::trainedOnBalls(dim, n, {type, gamma, block, wholeShare}, beta, 101, 7);
}

struct AgreementCase {
  std::size_t dim;
  KernelType type;
  double gamma, beta;
  std::uint32_t block = 0;
  double wholeShare = 0;
};

class FloatPath : public ::testing::TestWithParam<AgreementCase> {};

// The vectorised float path must give the double path's sign on at least 99.99% of queries.
TEST_P(FloatPath, AgreesInSignWithTheDoublePath) {
  const auto c = GetParam();
#ifdef FASTRON_SANITIZED
  // The sanitizers look for memory errors, which a twentieth of the queries and a sixth of the
  // training points reach as well (the 19- and 12-feature cases, random labels, every point a
  // support point, took 22 and 15 s of the sanitizer stage with 1000 points and 10000 queries).
  const std::size_t points = 500, queries = 5'000;
#else
  const std::size_t points = 3000, queries = 100'000;
#endif
  const auto model = trainedModel(c.dim, points, c.type, c.gamma, c.beta, c.block, c.wholeShare);
  ASSERT_GT(model->supportCount(), 50u);
  const Configurations q = test::uniformPoints(queries, c.dim, 103);
  std::size_t disagreements = 0;
  double worst = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const double fast = model->score(q.row(i).data());
    const double exact = model->scoreExact(q.row(i).data());
    disagreements += (fast > 0) != (exact > 0);
    worst = std::max(worst, std::abs(fast - exact) / (1 + std::abs(exact)));
  }
  RecordProperty("disagreements", static_cast<int>(disagreements));
  EXPECT_LE(disagreements, std::max<std::size_t>(1, queries / 10'000))
      << disagreements << " sign disagreements";
  EXPECT_LT(worst, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Kernels, FloatPath,
                         ::testing::Values(AgreementCase{2, KernelType::RationalQuadratic, 30, 1},
                                           AgreementCase{4, KernelType::RationalQuadratic, 10, 100},
                                           AgreementCase{7, KernelType::RationalQuadratic, 5, 500},
                                           AgreementCase{4, KernelType::Gaussian, 10, 1},
                                           AgreementCase{19, KernelType::RationalQuadratic, 3, 1},
                                           AgreementCase{12, KernelType::RationalQuadratic, 10, 10,
                                                         3, 0.2},
                                           AgreementCase{6, KernelType::Gaussian, 10, 1, 3, 0}),
                         [](const auto& info) {
                           return std::to_string(info.param.dim) + "d_" +
                                  std::string(toString(info.param.type)) + "_beta" +
                                  std::to_string(static_cast<int>(info.param.beta)) +
                                  (info.param.block ? "_points" : "");
                         });

TEST(Model, ScoreIsTheWeightedKernelSumInInputSpace) {
  const JointLimits limits(Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 4));
  Eigen::MatrixXd s(2, 2);
  s << 0, 0, 0.5, -0.5;
  const Model model =
      *jointSpaceModel(limits, {KernelType::RationalQuadratic, 2}, s, Eigen::Vector2d(1.5, -0.25));
  const std::vector<double> q{1.5, 1.0};  // input space (0.5, -0.5): on the second point
  const double r2 = 0.5;                  // to the first point
  const double expected = 1.5 / ((1 + r2) * (1 + r2)) - 0.25;
  EXPECT_NEAR(model.scoreExact(q.data()), expected, 1e-12);
  EXPECT_NEAR(model.score(q), expected, 1e-6);
  EXPECT_EQ(model.inCollision(q), expected > 0);
}

TEST(Model, BatchScoresEqualSingleScores) {
  const auto model = trainedModel(3, 1000, KernelType::RationalQuadratic, 10, 1);
  const Configurations q = test::uniformPoints(257, 3, 104);
  const Eigen::VectorXd batch = model->scoreBatch(q);
  for (Eigen::Index i = 0; i < q.rows(); ++i) EXPECT_EQ(batch[i], model->score(q.row(i).data()));
}

// The single query unrolls its loop over features for the usual dimensions and loops for the
// others, with one term or with point terms; each must equal the double sum to float rounding and
// the batch path exactly.
TEST(Model, EveryDimensionScoresAlikeOnEveryPath) {
  for (std::size_t dim = 1; dim <= 15; ++dim) {
    for (const KernelType type : {KernelType::RationalQuadratic, KernelType::Gaussian}) {
      std::vector<Kernel> kernels{{type, 3}};
      if (dim % 3 == 0) kernels.push_back({type, 3, 3, 0.3});
      if (dim % 2 == 0) kernels.push_back({type, 3, 2, 0});
      for (const Kernel& kernel : kernels) {
        const Configurations s = test::uniformPoints(37, dim, 200 + dim);  // 37: a padded block
        const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(37, -1.0, 0.8);
        const Model model(FeatureMap::jointScaling(JointLimits::unitBox(dim)), kernel, s, w);
        const Configurations q = test::uniformPoints(9, dim, 300 + dim);
        const Eigen::VectorXd batch = model.scoreBatch(q);
        for (Eigen::Index i = 0; i < q.rows(); ++i) {
          const std::string where = "d " + std::to_string(dim) + " " + std::string(toString(type)) +
                                    " block " + std::to_string(kernel.block) + " row " +
                                    std::to_string(i);
          const double single = model.score(q.row(i).data());
          EXPECT_NEAR(single, model.scoreExact(q.row(i).data()), 1e-5) << where;
          EXPECT_EQ(batch[i], single) << where;
        }
      }
    }
  }
}

TEST(Model, FirstInCollisionIsTheFirstRowPredictedInCollision) {
  const auto model = trainedModel(3, 1000, KernelType::RationalQuadratic, 10, 1);
  const Configurations q = test::uniformPoints(300, 3, 105);
  for (const std::size_t n : {0u, 1u, 3u, 4u, 5u, 9u, 300u}) {
    for (std::size_t offset = 0; offset + n <= 300; offset += 37) {
      std::size_t expected = n;
      for (std::size_t i = 0; i < n && expected == n; ++i) {
        if (model->inCollision(q.row(static_cast<Eigen::Index>(offset + i)).data())) expected = i;
      }
      EXPECT_EQ(model->firstInCollision(q.row(static_cast<Eigen::Index>(offset)).data(), n),
                expected)
          << "n " << n << ", offset " << offset;
      if (n == 0) break;
    }
  }
}

TEST(Model, RejectsBadConstructionAndQueries) {
  const FeatureMap limits = FeatureMap::jointScaling(JointLimits::unitBox(2));
  const Kernel kernel{};
  EXPECT_THROW(Model(limits, kernel, Configurations::Zero(3, 3), Eigen::VectorXd::Zero(3)),
               InvalidArgument);
  EXPECT_THROW(Model(limits, kernel, Configurations::Zero(3, 2), Eigen::VectorXd::Zero(2)),
               InvalidArgument);
  Configurations nan = Configurations::Zero(1, 2);
  nan(0, 1) = std::nan("");
  EXPECT_THROW(Model(limits, kernel, nan, Eigen::VectorXd::Ones(1)), InvalidArgument);
  EXPECT_THROW(Model(FeatureMap::jointScaling(JointLimits::unitBox(kMaxDimension + 1)), kernel,
                     Configurations::Zero(1, kMaxDimension + 1), Eigen::VectorXd::Ones(1)),
               InvalidArgument);

  const Model model(limits, kernel, Configurations::Zero(1, 2), Eigen::VectorXd::Ones(1));
  EXPECT_THROW(model.score(std::vector<double>{0.0}), InvalidArgument);
  EXPECT_THROW(model.score(std::vector<double>{0.0, std::nan("")}), InvalidArgument);
  EXPECT_THROW(model.scoreBatch(Configurations::Zero(4, 3)), InvalidArgument);
}

// Found by fuzz/model_fuzzer: model files whose weights, kernel width or support features lie
// beyond float range loaded, and then scored NaN (the queries compute in float, 0 * inf = NaN).
TEST(Model, RefusesValuesBeyondTheFloatRangeOfTheQueries) {
  const FeatureMap joints = FeatureMap::jointScaling(JointLimits::unitBox(2));
  const Configurations one = Configurations::Zero(1, 2);
  EXPECT_THROW(Model(joints, Kernel{}, one, Eigen::VectorXd::Constant(1, 1e39)), InvalidArgument);
  EXPECT_THROW(Model(joints, Kernel{KernelType::Gaussian, 1e-134}, one, Eigen::VectorXd::Ones(1)),
               InvalidArgument);
  EXPECT_THROW(Model(joints, Kernel{KernelType::Gaussian, 1e31}, one, Eigen::VectorXd::Ones(1)),
               InvalidArgument);
  const FeatureMap tiny =
      FeatureMap::jointScaling(JointLimits(Eigen::Vector2d(0, 0), Eigen::Vector2d(1e-300, 1e-300)));
  EXPECT_THROW(Model(tiny, Kernel{}, Configurations::Ones(1, 2), Eigen::VectorXd::Ones(1)),
               InvalidArgument);
  // The largest accepted values still score finitely.
  const Model large(joints, Kernel{KernelType::Gaussian, 1e-30}, one,
                    Eigen::VectorXd::Constant(1, 1e30));
  EXPECT_TRUE(std::isfinite(large.score(std::vector<double>{0.5, 0.5})));
}

}  // namespace
}  // namespace fastron
