// The kernel sums compiled for each instruction set (simd.h): every path this processor runs
// gives the double-precision sum within float rounding, single and batched scores are the same
// numbers on each path, and the paths agree with one another.

#include "fastron/core/simd.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "fastron/core/error.h"
#include "fastron/core/model.h"
#include "simd_path_guard.h"
#include "test_worlds.h"

namespace fastron {
namespace {

using test::SimdPathGuard;

Model randomModel(std::size_t dim, KernelType type, double gamma, unsigned seed) {
  const Configurations s = test::uniformPoints(53, dim, seed);  // 53: a partly padded block
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(53, -1.0, 0.8);
  return {FeatureMap::jointScaling(JointLimits::unitBox(dim)), {type, gamma}, s, w};
}

TEST(Simd, NamesRoundTripAndUnknownNamesAreRefused) {
  for (const SimdPath path : {SimdPath::Portable, SimdPath::Avx2, SimdPath::Avx512}) {
    EXPECT_EQ(parseSimdPath(toString(path)), path);
  }
  try {
    parseSimdPath("sse9");
    FAIL() << "sse9 was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("'sse9'"), std::string::npos) << e.what();
  }
}

TEST(Simd, SupportedPathsStartPortableAndIncludeTheActiveOne) {
  const std::vector<SimdPath> paths = supportedSimdPaths();
  ASSERT_FALSE(paths.empty());
  EXPECT_EQ(paths.front(), SimdPath::Portable);
  EXPECT_TRUE(std::is_sorted(paths.begin(), paths.end()));
  EXPECT_NE(std::find(paths.begin(), paths.end(), activeSimdPath()), paths.end());
}

TEST(Simd, EnvironmentRequestsAreCheckedAndNamed) {
  const std::vector<SimdPath> paths = supportedSimdPaths();
  EXPECT_EQ(simdPathFor(nullptr), paths.back());  // unset: the widest
  EXPECT_EQ(simdPathFor(""), paths.back());
  for (const SimdPath path : paths) {
    EXPECT_EQ(simdPathFor(std::string(toString(path)).c_str()), path);
  }
  try {
    simdPathFor("avx1024");
    FAIL() << "avx1024 was accepted";
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("FASTRON_SIMD"), std::string::npos) << message;
    EXPECT_NE(message.find("avx1024"), std::string::npos) << message;
  }
}

TEST(Simd, EveryPathGivesTheExactSumAndBatchesEqualSingles) {
  const SimdPathGuard guard;
  for (const SimdPath path : supportedSimdPaths()) {
    useSimdPath(path);
    ASSERT_EQ(activeSimdPath(), path);
    for (std::size_t dim = 1; dim <= 14; ++dim) {
      for (const KernelType type : {KernelType::RationalQuadratic, KernelType::Gaussian}) {
        const Model model = randomModel(dim, type, 3, 400 + static_cast<unsigned>(dim));
        const Configurations q = test::uniformPoints(11, dim, 500 + static_cast<unsigned>(dim));
        const Eigen::VectorXd batch = model.scoreBatch(q);
        for (Eigen::Index i = 0; i < q.rows(); ++i) {
          const double single = model.score(q.row(i).data());
          const std::string where = std::string(toString(path)) + ", d " + std::to_string(dim) +
                                    ", " + std::string(toString(type)) + ", row " +
                                    std::to_string(i);
          // 53 weights of at most 1: float rounding of each term stays far below 1e-5.
          EXPECT_NEAR(single, model.scoreExact(q.row(i).data()), 1e-5) << where;
          EXPECT_EQ(batch[i], single) << where;
        }
      }
    }
  }
}

TEST(Simd, PathsAgreeWithOneAnother) {
  const SimdPathGuard guard;
  const std::vector<SimdPath> paths = supportedSimdPaths();
  for (const KernelType type : {KernelType::RationalQuadratic, KernelType::Gaussian}) {
    const Model model = randomModel(12, type, 5, 77);
    const Configurations q = test::uniformPoints(200, 12, 78);
    useSimdPath(SimdPath::Portable);
    const Eigen::VectorXd reference = model.scoreBatch(q);
    for (const SimdPath path : paths) {
      useSimdPath(path);
      const Eigen::VectorXd scores = model.scoreBatch(q);
      // With and without fused multiply-adds, sums of 53 terms of at most 1 differ in the last
      // bits of float: 1e-5 absolute is about a hundred times that.
      EXPECT_LE((scores - reference).cwiseAbs().maxCoeff(), 1e-5) << toString(path);
    }
  }
}

TEST(Simd, GaussianKernelFollowsExpDownToUnderflow) {
  const SimdPathGuard guard;
  // One support point at the origin with weight 1: the score is exp(-gamma r^2) itself.
  const Configurations origin = Configurations::Zero(1, 1);
  const Model model(FeatureMap::jointScaling(JointLimits::unitBox(1)), {KernelType::Gaussian, 100},
                    origin, Eigen::VectorXd::Ones(1));
  for (const SimdPath path : supportedSimdPaths()) {
    useSimdPath(path);
    for (double x = 0; x <= 1.0; x += 1.0 / 1024) {
      // The exponent as the float path computes it: its rounding alone moves exp by up to
      // |exponent| * 6e-8 relative (5e-6 near underflow), for every exp in float.
      const auto xf = static_cast<float>(x);
      const double exact = std::exp(static_cast<double>(-100.0f * (xf * xf)));
      const double score = model.score(&x);
      if (exact > 1e-37) {
        EXPECT_NEAR(score, exact, 4e-7 * exact) << toString(path) << ", x " << x;
      } else {
        EXPECT_GE(score, 0.0) << toString(path) << ", x " << x;
        EXPECT_LE(score, 2e-37) << toString(path) << ", x " << x;  // exp(-87) at most
      }
    }
  }
}

TEST(Simd, SwitchingPathsWhileOtherThreadsQueryIsSafe) {
  const SimdPathGuard guard;
  const Model model = randomModel(7, KernelType::RationalQuadratic, 5, 91);
  const Configurations q = test::uniformPoints(64, 7, 92);
  const Eigen::VectorXd expected = model.scoreBatch(q);
  std::atomic<bool> stop{false};
  std::atomic<int> far{0};
  std::vector<std::thread> readers;
  for (int t = 0; t < 2; ++t) {
    readers.emplace_back([&] {
      while (!stop.load()) {
        for (Eigen::Index i = 0; i < q.rows(); ++i) {
          if (std::abs(model.score(q.row(i).data()) - expected[i]) > 1e-5) ++far;
        }
      }
    });
  }
  const std::vector<SimdPath> paths = supportedSimdPaths();
  for (int k = 0; k < 300; ++k) useSimdPath(paths[static_cast<std::size_t>(k) % paths.size()]);
  stop = true;
  for (std::thread& t : readers) t.join();
  EXPECT_EQ(far.load(), 0);
}

}  // namespace
}  // namespace fastron
