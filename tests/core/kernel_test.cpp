#include "fastron/core/kernel.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "fastron/core/error.h"
#include "fastron/core/joint_limits.h"
#include "temp_dir.h"

namespace fastron {
namespace {

using test::messageOf;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

TEST(Kernel, RationalQuadraticMatchesItsFormula) {
  const Kernel k{KernelType::RationalQuadratic, 4};
  EXPECT_DOUBLE_EQ(k(0.0), 1.0);
  EXPECT_DOUBLE_EQ(k(0.5), 1.0 / ((1 + 2 * 0.5) * (1 + 2 * 0.5)));
  EXPECT_FLOAT_EQ(k(0.5f), 0.25f);
}

TEST(Kernel, GaussianMatchesItsFormula) {
  const Kernel k{KernelType::Gaussian, 3};
  EXPECT_DOUBLE_EQ(k(0.0), 1.0);
  EXPECT_DOUBLE_EQ(k(0.2), std::exp(-0.6));
}

TEST(Kernel, RationalQuadraticApproachesTheGaussianFromAbove) {
  // (1 + gamma r2 / p)^-p >= exp(-gamma r2) for p = 2, and both decrease with distance.
  const Kernel rq{KernelType::RationalQuadratic, 1}, g{KernelType::Gaussian, 1};
  double previous = 2;
  for (double r2 = 0.01; r2 < 10; r2 *= 1.5) {
    EXPECT_GE(rq(r2), g(r2));
    EXPECT_LT(rq(r2), previous);
    previous = rq(r2);
  }
}

TEST(Kernel, NamesAndValidation) {
  EXPECT_EQ(parseKernelType("rq"), KernelType::RationalQuadratic);
  EXPECT_EQ(parseKernelType("gaussian"), KernelType::Gaussian);
  EXPECT_EQ(toString(KernelType::Gaussian), "gaussian");
  EXPECT_THROW(parseKernelType("linear"), InvalidArgument);
  EXPECT_THROW(validate(Kernel{KernelType::RationalQuadratic, 0}), InvalidArgument);
  EXPECT_THROW(validate(Kernel{KernelType::RationalQuadratic, std::nan("")}), InvalidArgument);
}

TEST(Kernel, PointTermsAreTheWeightedMeanOfTheBlocksAndTheWholeVector) {
  const std::array<double, 6> a{0, 0, 0, 1, 2, 2}, b{0.3, 0.4, 0, 1, 2, 1};
  const auto of = [](const std::array<double, 6>& v) {
    return [&v](std::size_t c) { return v[c]; };
  };
  const Kernel one{KernelType::RationalQuadratic, 2};
  const double whole = one(0.25 + 1.0);
  EXPECT_DOUBLE_EQ(one.between<double>(of(a), of(b), 6), whole);
  const Kernel points{KernelType::RationalQuadratic, 2, 3, 0.2};
  EXPECT_DOUBLE_EQ(points.between<double>(of(a), of(b), 6),
                   0.2 * whole + 0.8 / 2 * (one(0.25) + one(1.0)));
  const Kernel gaussian{KernelType::Gaussian, 2, 2, 0};
  EXPECT_DOUBLE_EQ(gaussian.between<double>(of(a), of(b), 6),
                   (std::exp(-2 * 0.25) + std::exp(-2 * 0.0) + std::exp(-2 * 1.0)) / 3);
  for (const Kernel& k : {one, points, gaussian})
    EXPECT_DOUBLE_EQ(k.between<double>(of(a), of(a), 6), 1);
  EXPECT_EQ(points.pointTerms(6), 2u);
  EXPECT_EQ(describeTerms(one, 6), "one term");
  EXPECT_EQ(describeTerms(points, 6),
            "a term per 3 features (2) and the whole vector's, share 0.2");
  EXPECT_EQ(describeTerms(gaussian, 6), "a term per 2 features (3), no whole-vector term");
}

TEST(Kernel, PointTermsMustDivideTheFeaturesAndShareIsAFraction) {
  EXPECT_NO_THROW(validate(Kernel{KernelType::RationalQuadratic, 1, 3, 0.5}, 12));
  EXPECT_THAT(messageOf<InvalidArgument>([] {
                validate(Kernel{KernelType::RationalQuadratic, 1, 5, 0}, 12);
              }),
              HasSubstr("kernel block 5 does not divide the feature dimension 12"));
  EXPECT_THAT(messageOf<InvalidArgument>([] {
                validate(Kernel{KernelType::RationalQuadratic, 1, 3, 1.5}, 12);
              }),
              HasSubstr("whole-vector share must be between 0 and 1"));
}

TEST(JointLimits, MapsLimitsToMinusOneAndOne) {
  const JointLimits limits(Eigen::Vector3d(-3.14, 0, -1), Eigen::Vector3d(3.14, 3.14, 3));
  const Eigen::VectorXd lo = limits.toInput(std::vector<double>{-3.14, 0, -1});
  const Eigen::VectorXd hi = limits.toInput(std::vector<double>{3.14, 3.14, 3});
  const Eigen::VectorXd mid = limits.toInput(std::vector<double>{0, 1.57, 1});
  EXPECT_TRUE(lo.isApprox(Eigen::Vector3d::Constant(-1)));
  EXPECT_TRUE(hi.isApprox(Eigen::Vector3d::Constant(1)));
  EXPECT_NEAR(mid.norm(), 0, 1e-12);
  const Eigen::VectorXd back = limits.toJoint(std::vector<double>{0.5, -0.5, 0});
  EXPECT_NEAR(back[0], 1.57, 1e-12);
  EXPECT_NEAR(back[1], 0.785, 1e-12);
  EXPECT_NEAR(back[2], 1, 1e-12);
}

TEST(JointLimits, RejectsBadLimitsAndConfigurations) {
  EXPECT_THROW(JointLimits(Eigen::Vector2d(0, 1), Eigen::Vector2d(1, 1)), InvalidArgument);
  EXPECT_THROW(JointLimits(Eigen::Vector2d(0, 2), Eigen::Vector2d(1, 1)), InvalidArgument);
  EXPECT_THROW(JointLimits(Eigen::Vector2d(0, 0), Eigen::Vector3d(1, 1, 1)), InvalidArgument);
  EXPECT_THROW(JointLimits(Eigen::Vector2d(0, std::nan("")), Eigen::Vector2d(1, 1)),
               InvalidArgument);
  // Spans that scale to inf or NaN features: subnormal (a fuzzed model file's), beyond double.
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [] { JointLimits(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 2.59e-318)); }),
              ::testing::HasSubstr("joint limits of joint 1"));
  EXPECT_THROW(JointLimits(Eigen::Vector2d(-1e308, 0), Eigen::Vector2d(1e308, 1)), InvalidArgument);
  EXPECT_NO_THROW(JointLimits(Eigen::Vector2d(0, -1e-300), Eigen::Vector2d(1e-300, 1e300)));
  const JointLimits limits = JointLimits::unitBox(2);
  EXPECT_THROW(limits.toInput(std::vector<double>{0.0}), InvalidArgument);
  EXPECT_THROW(limits.toInput(std::vector<double>{0.0, INFINITY}), InvalidArgument);
  try {
    checkConfiguration(std::vector<double>{0.0, std::nan("")}, 2);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("[1]"), std::string::npos) << e.what();
  }
}

// Data without limits gets its bounding box; no rows, or a constant column, say what to give.
TEST(JointLimits, RangeOfData) {
  Configurations q(3, 2);
  q << 0, -1, 2, 0.5, 1, 3;
  const JointLimits range = rangeOf(q, "give limits");
  EXPECT_EQ(range.lower(), Eigen::Vector2d(0, -1));
  EXPECT_EQ(range.upper(), Eigen::Vector2d(2, 3));
  EXPECT_THAT([] { rangeOf(Configurations(0, 2), "give limits"); },
              ThrowsMessage<InvalidArgument>(HasSubstr("no configurations")));
  q.col(1).setConstant(4);
  EXPECT_THAT([&] { rangeOf(q, "give --limits"); },
              ThrowsMessage<InvalidArgument>(
                  AllOf(HasSubstr("joint 1"), HasSubstr("data's range; give --limits"))));
}

}  // namespace
}  // namespace fastron
