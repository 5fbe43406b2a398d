#include "fastron/core/support_reduction.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fastron/core/error.h"
#include "fastron/core/trainer.h"
#include "temp_dir.h"
#include "test_worlds.h"

namespace fastron {
namespace {

using test::messageOf;
using ::testing::HasSubstr;

std::shared_ptr<const Model> ballWorldModel() {
  const std::size_t dim = 3, n = 3000;
  const Configurations q = test::uniformPoints(n, dim, 201);
  TrainParams p;
  p.kernel = {KernelType::RationalQuadratic, 10};
  p.maxIterations = 100'000;
  p.maxSupportPoints = n;
  Trainer trainer(JointLimits::unitBox(dim), p);
  trainer.addPoints(q, test::BallWorld::random(dim, 4, 0.4, 202).label(q));
  trainer.update();
  return trainer.model();
}

/// Model a with the support set of b: b's rows are a's rows (same configuration, same weight).
void expectSubsetOf(const Model& b, const Model& a) {
  for (Eigen::Index i = 0; i < b.supportConfigurations().rows(); ++i) {
    bool found = false;
    for (Eigen::Index j = 0; j < a.supportConfigurations().rows() && !found; ++j) {
      found = a.supportConfigurations().row(j) == b.supportConfigurations().row(i) &&
              a.weights()[j] == b.weights()[i];
    }
    EXPECT_TRUE(found) << "support point " << i << " is not one of the original's";
  }
}

TEST(PruneSupport, KeepsEveryHeldOutAnswerWithASubsetOfTheSupportSet) {
  // A trained model with 50 points of weight 1e-4 added: no answer should need them.
  const auto trained = ballWorldModel();
  const auto n = static_cast<Eigen::Index>(trained->supportCount());
  Configurations support(n + 50, 3);
  support << trained->supportConfigurations(), test::uniformPoints(50, 3, 206);
  Eigen::VectorXd weights(n + 50);
  weights << trained->weights(), Eigen::VectorXd::Constant(50, 1e-4);
  const auto model =
      std::make_shared<const Model>(trained->features(), trained->kernel(), support, weights);
  const Configurations heldOut = test::uniformPoints(2000, 3, 203);
  const auto pruned = pruneSupport(*model, heldOut);
  EXPECT_LE(pruned->supportCount(), trained->supportCount());
  expectSubsetOf(*pruned, *model);
  for (Eigen::Index i = 0; i < heldOut.rows(); ++i) {
    ASSERT_EQ(pruned->scoreExact(heldOut.row(i).data()) > 0,
              model->scoreExact(heldOut.row(i).data()) > 0)
        << "held-out row " << i;
  }
}

TEST(PruneSupport, DropsAPointNoAnswerNeeds) {
  // Two points of one sign far apart and a third, tiny weight next to the first: no answer on
  // the held-out points depends on the third.
  const JointLimits limits = JointLimits::unitBox(2);
  Configurations support(3, 2);
  support << -0.5, 0.0, 0.5, 0.0, -0.45, 0.0;
  const Model model(FeatureMap::jointScaling(limits), {KernelType::RationalQuadratic, 20}, support,
                    Eigen::Vector3d(1.0, -1.0, 1e-3));
  const auto pruned = pruneSupport(model, test::uniformPoints(500, 2, 204));
  ASSERT_EQ(pruned->supportCount(), 2u);
  EXPECT_EQ(pruned->weights(), Eigen::Vector2d(1.0, -1.0));
  // Without held-out points, nothing constrains the answers: every point may go.
  EXPECT_EQ(pruneSupport(model, Configurations(0, 2))->supportCount(), 0u);
}

TEST(PruneSupport, RefusesHeldOutPointsOfTheWrongShapeOrNotFinite) {
  const auto model = ballWorldModel();
  EXPECT_THAT(messageOf<InvalidArgument>([&] { pruneSupport(*model, Configurations(4, 2)); }),
              HasSubstr("2 columns, expected 3"));
  Configurations bad = test::uniformPoints(4, 3, 205);
  bad(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(pruneSupport(*model, bad), InvalidArgument);
}

TEST(MergeSupport, MergesPointsOfOneSignWithinTheRadiusAndKeepsTheirWeight) {
  const JointLimits limits = JointLimits::unitBox(2);
  Configurations support(4, 2);
  // Scaled joint space is the unit box itself: features equal configurations.
  support << 0.0, 0.0, 0.05, 0.0, 0.08, 0.0, 0.5, 0.5;
  const Model model(FeatureMap::jointScaling(limits), {KernelType::RationalQuadratic, 20}, support,
                    Eigen::Vector4d(2.0, 0.5, -1.0, 1.0));
  const auto merged = mergeSupport(model, 0.1);
  // 0.05 joins 0.0 (same sign, 0.05 apart); 0.08 has the other sign; 0.5 is far.
  ASSERT_EQ(merged->supportCount(), 3u);
  EXPECT_EQ(merged->supportConfigurations().row(0), Eigen::RowVector2d(0.0, 0.0));
  EXPECT_EQ(merged->weights(), Eigen::Vector3d(2.5, -1.0, 1.0));
  EXPECT_NEAR(merged->weights().sum(), model.weights().sum(), 1e-12);
  EXPECT_EQ(mergeSupport(model, 0.0)->supportCount(), 4u);
  for (const double bad :
       {-1.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_THAT(messageOf<InvalidArgument>([&] { mergeSupport(model, bad); }),
                HasSubstr("merge radius must be finite and >= 0"));
  }
}

}  // namespace
}  // namespace fastron
