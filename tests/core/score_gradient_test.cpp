// Model::scoreGradient: the analytic gradient agrees with central differences of scoreExact for
// every kernel (rational quadratic, Gaussian; one term, and point terms beside the whole vector's)
// on joint-space features. Kinematic features: tests/geometry/control_points_test.cpp.

#include <gtest/gtest.h>

#include "fastron/core/error.h"
#include "fastron/core/model.h"
#include "fastron/core/simd.h"
#include "finite_differences.h"
#include "simd_path_guard.h"
#include "test_worlds.h"

namespace fastron {
namespace gradient_test {

/// A model of random support points and weights in [-1, 1]^dim (no training: every weight and
/// point counts, near ones and far ones).
Model randomModel(std::size_t dim, Kernel kernel, std::uint64_t seed) {
  const Configurations support = test::uniformPoints(40, dim, seed);
  Rng rng(seed + 1);
  std::uniform_real_distribution<double> weight(-2, 2);
  Eigen::VectorXd weights(support.rows());
  for (auto& w : weights) w = weight(rng);
  return Model(FeatureMap::jointScaling(JointLimits::unitBox(dim)), kernel, support, weights);
}

struct KernelCase {
  KernelType type;
  double gamma;
  std::uint32_t block;
  double wholeShare;
};

TEST(ScoreGradient, AgreesWithCentralDifferencesForEveryKernelOnBothPaths) {
  const std::vector<KernelCase> cases{{KernelType::RationalQuadratic, 5, 0, 0},
                                      {KernelType::Gaussian, 3, 0, 0},
                                      {KernelType::RationalQuadratic, 8, 3, 0.5},
                                      {KernelType::Gaussian, 2, 3, 0.2},
                                      {KernelType::RationalQuadratic, 8, 2, 0}};
  for (const KernelCase& c : cases) {
    const Model model = randomModel(6, {c.type, c.gamma, c.block, c.wholeShare}, 7);
    const Configurations q = test::uniformPoints(50, 6, 9);
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      const Eigen::VectorXd row = q.row(i);
      const Model::ScoreGradient exact = model.scoreGradientExact({row.data(), 6});
      EXPECT_NEAR(exact.score, model.scoreExact(row.data()), 1e-12);
      // Step 1e-5: the differences' own error (h^2 times the third derivative) is far below the
      // tolerance.
      const Eigen::VectorXd numeric =
          test::centralDifferences([&](const double* x) { return model.scoreExact(x); }, row, 1e-5);
      const double scale = std::max(numeric.lpNorm<Eigen::Infinity>(), 1e-3);
      ASSERT_LE((exact.gradient - numeric).lpNorm<Eigen::Infinity>(), 1e-4 * scale)
          << "kernel " << static_cast<int>(c.type) << " block " << c.block << " row " << i;
      // The float path: the same within float's precision over 40 terms.
      const Model::ScoreGradient fast = model.scoreGradient({row.data(), 6});
      EXPECT_NEAR(fast.score, exact.score, 1e-5 * std::max(1.0, std::abs(exact.score)));
      ASSERT_LE((fast.gradient - exact.gradient).lpNorm<Eigen::Infinity>(), 1e-4 * scale)
          << "float path, kernel " << static_cast<int>(c.type) << " block " << c.block;
    }
  }
}

// The kernel sums unroll the shapes of 2-, 7-joint and 3-, 4-point models (kernel_sums_impl.h):
// every shape, one-term and with point terms, on every SIMD path, agrees with the double sum.
TEST(ScoreGradient, EveryUnrolledShapeOnEverySimdPathAgreesWithTheDoubleSum) {
  const test::SimdPathGuard guard;
  struct Shape {
    std::size_t dim;
    std::uint32_t block;
  };
  for (const SimdPath path : supportedSimdPaths()) {
    useSimdPath(path);
    for (const Shape shape : {Shape{2, 0}, Shape{7, 0}, Shape{12, 0}, Shape{9, 3}, Shape{12, 3},
                              Shape{5, 0}, Shape{8, 4}}) {
      for (const KernelType type : {KernelType::RationalQuadratic, KernelType::Gaussian}) {
        const Model model =
            randomModel(shape.dim, {type, 4, shape.block, shape.block == 0 ? 0.0 : 0.5}, 21);
        const Configurations q = test::uniformPoints(10, shape.dim, 22);
        for (Eigen::Index i = 0; i < q.rows(); ++i) {
          const Eigen::VectorXd row = q.row(i);
          const Model::ScoreGradient exact = model.scoreGradientExact({row.data(), shape.dim});
          const Model::ScoreGradient fast = model.scoreGradient({row.data(), shape.dim});
          const double scale = std::max(exact.gradient.lpNorm<Eigen::Infinity>(), 1e-3);
          EXPECT_NEAR(fast.score, exact.score, 1e-5 * std::max(1.0, std::abs(exact.score)));
          ASSERT_LE((fast.gradient - exact.gradient).lpNorm<Eigen::Infinity>(), 1e-4 * scale)
              << toString(path) << " dim " << shape.dim << " block " << shape.block;
        }
      }
    }
  }
}

TEST(ScoreGradient, BatchesAgreeWithSingleQueriesAndBadInputIsRefused) {
  const Model model = randomModel(4, {KernelType::RationalQuadratic, 5, 0, 0}, 3);
  const Configurations q = test::uniformPoints(20, 4, 4);
  const Model::ScoreGradients batch = model.scoreGradients(q);
  ASSERT_EQ(batch.gradients.rows(), 20);
  ASSERT_EQ(batch.gradients.cols(), 4);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const Eigen::VectorXd row = q.row(i);
    const Model::ScoreGradient one = model.scoreGradient({row.data(), 4});
    EXPECT_DOUBLE_EQ(batch.scores[i], one.score);
    EXPECT_TRUE(batch.gradients.row(i).transpose().isApprox(one.gradient));
  }
  const std::vector<double> three{0, 0, 0}, nan{0, 0, std::nan(""), 0};
  EXPECT_THROW((void)model.scoreGradient(three), InvalidArgument);
  EXPECT_THROW((void)model.scoreGradient(nan), InvalidArgument);
  EXPECT_THROW((void)model.scoreGradientExact(three), InvalidArgument);
  EXPECT_THROW((void)model.scoreGradients(Configurations(2, 3)), InvalidArgument);
}

}  // namespace gradient_test
}  // namespace fastron
