#include "fastron/core/point_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <thread>
#include <utility>

#include "fastron/core/error.h"
#include "fastron/core/model.h"
#include "test_worlds.h"

namespace fastron {
namespace {

/// A model of point terms only (block 3, no whole term) on `dim` joints of the unit box.
std::shared_ptr<const Model> pointTermModel(std::size_t dim, std::size_t n, KernelType type,
                                            double gamma, double beta) {
  return test::trainedOnBalls(dim, n, {type, gamma, 3, 0}, beta, 401, 9);
}

/// The field's own verdict on q: +1, -1, or 0 when it leaves q to the full sum.
int fieldSign(const Model& model, const double* q) {
  std::array<float, kMaxFeatureDimension> x{};
  model.features().map(q, x.data());
  return model.pointField()->sign(x.data());
}

struct FieldCase {
  std::size_t dim;
  KernelType type;
  double gamma, beta, spacing;
  double decidedShare;  ///< the least share of queries the grids must answer themselves
};

class PointFieldAnswers : public ::testing::TestWithParam<FieldCase> {};

// Every answer of a model with a field equals the full sum's sign (score > 0), on uniform queries
// and on queries within float rounding of the decision boundary; most of them come from the
// grids, and score itself is unchanged.
TEST_P(PointFieldAnswers, AsTheFullSumDoes) {
  const FieldCase c = GetParam();
#ifdef FASTRON_SANITIZED
  const std::size_t points = 600, queries = 3000;
#else
  const std::size_t points = 2000, queries = 20'000;
#endif
  const auto model = pointTermModel(c.dim, points, c.type, c.gamma, c.beta);
  PointFieldOptions options;
  options.spacing = c.spacing;
  options.refinement = 1;
  const auto tabulated = model->withPointField(options);
  ASSERT_NE(tabulated->pointField(), nullptr);
  EXPECT_EQ(model->pointField(), nullptr);
  EXPECT_EQ(tabulated->pointField()->grids().size(), c.dim / 3);
  EXPECT_EQ(tabulated->pointField()->fineBlockCount(), 0u);
  // The same grids with fine blocks wherever a bound is above rounding.
  options.refinement = c.dim == 6 ? 4 : 2;
  options.fineFrom = 0;
  const auto refined = model->withPointField(options);
  const PointField& fine = *refined->pointField();
  EXPECT_GT(fine.fineBlockCount(), 0u);

  const Configurations q = test::uniformPoints(queries, c.dim, 403);
  std::size_t decided = 0, decidedFinely = 0, collides = 0;
  std::array<float, kMaxFeatureDimension> x{};
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const double* row = q.row(i).data();
    const double score = model->score(row);
    ASSERT_EQ(tabulated->score(row), score);
    ASSERT_EQ(tabulated->inCollision(row), score > 0) << "query " << i << ", score " << score;
    ASSERT_EQ(refined->inCollision(row), score > 0) << "query " << i << ", score " << score;
    const int sign = fieldSign(*tabulated, row);
    if (sign != 0) {
      ASSERT_EQ(sign > 0, score > 0) << "query " << i;
    }
    model->features().map(row, x.data());
    const int fineSign = fine.signWithFineBlocks(x.data());
    if (fineSign != 0) {
      ASSERT_EQ(fineSign > 0, score > 0) << "query " << i;
    }
    ASSERT_TRUE(sign == 0 || fineSign == sign) << "query " << i;
    decided += sign != 0;
    decidedFinely += fineSign != 0;
    collides += score > 0;
  }
  ASSERT_GT(collides, queries / 200) << "the model should predict some collisions";
  EXPECT_GE(static_cast<double>(decided) / static_cast<double>(queries), c.decidedShare);
  // Fine blocks decide some of what the grids leave, and never fewer.
  EXPECT_GT(decidedFinely, decided);

  // Bisect segments between a colliding and a free query down to where the score changes sign:
  // both ends lie within rounding of f = 0, where an estimate could err.
  std::size_t boundary = 0;
  for (Eigen::Index i = 0; i + 1 < q.rows() && boundary < 50; i += 2) {
    Eigen::VectorXd a = q.row(i).transpose(), b = q.row(i + 1).transpose();
    if ((model->score(a.data()) > 0) == (model->score(b.data()) > 0)) continue;
    for (int step = 0; step < 60; ++step) {
      const Eigen::VectorXd mid = 0.5 * (a + b);
      ((model->score(mid.data()) > 0) == (model->score(a.data()) > 0) ? a : b) = mid;
    }
    for (const Eigen::VectorXd* end : {&a, &b}) {
      ASSERT_EQ(tabulated->inCollision(end->data()), model->score(end->data()) > 0)
          << "boundary query near segment " << i;
      ASSERT_EQ(refined->inCollision(end->data()), model->score(end->data()) > 0)
          << "boundary query near segment " << i << ", fine blocks";
    }
    ++boundary;
  }
  EXPECT_GE(boundary, 10u);
}

INSTANTIATE_TEST_SUITE_P(
    Kernels, PointFieldAnswers,
    ::testing::Values(FieldCase{3, KernelType::RationalQuadratic, 10, 1, 0.04, 0.9},
                      FieldCase{6, KernelType::RationalQuadratic, 10, 10, 0.05, 0.8},
                      FieldCase{9, KernelType::Gaussian, 10, 1, 0.05, 0.8},
                      FieldCase{6, KernelType::Gaussian, 30, 30, 0.04, 0.8},
                      FieldCase{27, KernelType::RationalQuadratic, 3, 1, 0.05, 0.5}),
    [](const auto& info) {
      return std::to_string(info.param.dim) + "d_" + std::string(toString(info.param.type)) +
             "_beta" + std::to_string(static_cast<int>(info.param.beta));
    });

TEST(PointField, FirstInCollisionEqualsTheFullSums) {
  const auto model = pointTermModel(6, 1000, KernelType::RationalQuadratic, 10, 1);
  const auto tabulated = model->withPointField();
  const Configurations q = test::uniformPoints(400, 6, 404);
  for (const std::size_t n : {0u, 1u, 5u, 17u, 40u, 400u}) {
    for (std::size_t offset = 0; offset + n <= 400; offset += 41) {
      const double* rows = q.row(static_cast<Eigen::Index>(offset)).data();
      EXPECT_EQ(tabulated->firstInCollision(rows, n), model->firstInCollision(rows, n))
          << "n " << n << ", offset " << offset;
      if (n == 0) break;
    }
  }
}

// Answers by the estimate alone (FieldAnswers::Estimate) are the sign of the grids' summed
// estimates; they differ from the full sum's only where the full sum lies within the estimates'
// summed bounds (on the model's boundary), and rarely; beyond the grids the full sum answers. No
// fine blocks are built, and edges answer as their states do.
TEST(PointField, EstimatedAnswersDifferFromTheFullSumOnlyWithinTheBounds) {
  for (const auto& [dim, beta] :
       {std::pair{std::size_t{6}, 1.0}, std::pair{std::size_t{9}, 10.0}}) {
    SCOPED_TRACE(std::to_string(dim) + " features");
    const auto model = pointTermModel(dim, 1500, KernelType::RationalQuadratic, 10, beta);
    PointFieldOptions options;
    options.answers = FieldAnswers::Estimate;
    options.fineFrom = 0;  // would build fine blocks for exact answers
    options.refinement = 2;
    const auto estimated = model->withPointField(options);
    const PointField& field = *estimated->pointField();
    EXPECT_EQ(field.answers(), FieldAnswers::Estimate);
    EXPECT_EQ(field.fineBlockCount(), 0u);
    const Configurations q = test::uniformPoints(20'000, dim, 411);
    std::size_t differ = 0, collides = 0, undecided = 0;
    std::array<float, kMaxFeatureDimension> x{};
    std::array<float, kMaxPointTerms> values{}, bounds{};
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      const double* row = q.row(i).data();
      const double score = model->score(row);
      const bool answer = estimated->inCollision(row);
      ASSERT_EQ(estimated->score(row), score);  // score still sums every term
      model->features().map(row, x.data());
      ASSERT_TRUE(field.estimateTerms(x.data(), values.data(), bounds.data())) << "query " << i;
      float value = 0, bound = 0;
      for (std::size_t g = 0; g < field.grids().size(); ++g) {
        value += values[g];
        bound += bounds[g];
      }
      ASSERT_EQ(answer, value > 0) << "query " << i;
      undecided += field.sign(x.data()) == 0;  // answered by the estimate, not by its bounds
      if (answer != (score > 0)) {
        ++differ;
        ASSERT_LE(std::abs(score), bound) << "query " << i << ": an answer off the boundary";
      }
      collides += score > 0;
    }
    ASSERT_GT(collides, q.rows() / 200) << "the model should predict some collisions";
    EXPECT_GT(undecided, 0u) << "no query left to the estimate alone";
    EXPECT_LT(differ, 200u) << "of " << q.rows();  // under 1%
    for (const std::size_t n : {1u, 16u, 40u}) {
      for (std::size_t offset = 0; offset + n <= 400; offset += 41) {
        const double* rows = q.row(static_cast<Eigen::Index>(offset)).data();
        std::size_t first = n;
        for (std::size_t k = 0; k < n && first == n; ++k) {
          if (estimated->inCollision(rows + k * dim)) first = k;
        }
        EXPECT_EQ(estimated->firstInCollision(rows, n), first) << "n " << n << ", " << offset;
      }
    }
  }
  // Beyond the grids (a box of two cells around one configuration) the full sum answers.
  const auto model = pointTermModel(3, 800, KernelType::RationalQuadratic, 10, 1);
  PointFieldOptions options;
  options.samples = 1;
  options.answers = FieldAnswers::Estimate;
  const auto estimated = model->withPointField(options);
  const Configurations q = test::uniformPoints(2000, 3, 412);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    ASSERT_EQ(estimated->inCollision(q.row(i).data()), model->score(q.row(i).data()) > 0);
  }
  EXPECT_EQ(parseFieldAnswers("estimate"), FieldAnswers::Estimate);
  EXPECT_EQ(parseFieldAnswers(toString(FieldAnswers::Exact)), FieldAnswers::Exact);
  try {
    (void)parseFieldAnswers("approximate");
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("'approximate'"), std::string::npos) << e.what();
  }
}

// A model of one point term has no other terms whose spare bounds could cover an error beyond its
// own: the grid's estimate must lie within its cell's bound of the exact term everywhere. The
// centre's error alone (errorFactor 1.5 on it, before the curvature correction, the axes' curvature
// left out) let the errors reach 1.84, 3.05 and 1.27 times their bounds here; with the axes'
// curvature the worst was 0.56-0.63, and with the correction and the spread of its curvatures
// 0.25-0.31.
TEST(PointField, EveryEstimateLiesWithinItsCellsBound) {
  for (const auto& [type, gamma] :
       {std::pair{KernelType::RationalQuadratic, 10.0},
        std::pair{KernelType::RationalQuadratic, 60.0}, std::pair{KernelType::Gaussian, 30.0}}) {
    SCOPED_TRACE(std::string(toString(type)) + " gamma " + std::to_string(gamma));
    const auto model = pointTermModel(3, 1500, type, gamma, 1);
    PointFieldOptions options;
    options.refinement = 1;
    const auto tabulated = model->withPointField(options);
    const Configurations q = test::uniformPoints(20'000, 3, 406);
    double worst = 0;
    Eigen::Index estimated = 0;
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      std::array<float, kMaxFeatureDimension> x{};
      model->features().map(q.row(i).data(), x.data());
      float value = 0, bound = 0;
      if (!tabulated->pointField()->estimateTerms(x.data(), &value, &bound)) continue;
      worst = std::max(worst, std::abs(model->scoreExact(q.row(i).data()) - value) / bound);
      ++estimated;
    }
    EXPECT_GT(estimated, q.rows() * 9 / 10);  // the grid covers the queries' box
    EXPECT_LT(worst, 1.0);
  }
}

// The curvature correction is what makes the grids sharp: on one-term models the corrected
// estimate errs several times less than the plain trilinear interpolation of the same nodes (5.0
// and 14 times less in the mean here).
TEST(PointField, CurvatureCorrectionSharpensTheEstimates) {
  for (const double gamma : {10.0, 60.0}) {
    SCOPED_TRACE("gamma " + std::to_string(gamma));
    const auto model = pointTermModel(3, 1500, KernelType::RationalQuadratic, gamma, 1);
    PointFieldOptions options;
    options.refinement = 1;
    const auto tabulated = model->withPointField(options);
    const PointField::Grid& grid = tabulated->pointField()->grids()[0];
    const Configurations q = test::uniformPoints(5000, 3, 407);
    double corrected = 0, plain = 0;
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      std::array<float, kMaxFeatureDimension> x{};
      model->features().map(q.row(i).data(), x.data());
      float t[3];
      std::uint32_t cell[3];
      if (!PointField::locate(grid, x.data(), cell, t)) continue;
      const std::size_t nx = grid.cells[0] + 1, nxy = nx * (grid.cells[1] + 1);
      const float* corners = grid.nodes.data() + cell[0] + nx * cell[1] + nxy * cell[2];
      const double exact = model->scoreExact(q.row(i).data());
      const PointField::Cell& record = grid.cellTable[PointField::cellIndex(grid, cell)];
      corrected += std::abs(PointField::estimate(corners, nx, nxy, record, t) - exact);
      plain += std::abs(PointField::trilinear(corners, nx, nxy, t) - exact);
    }
    EXPECT_LT(corrected * 2.5, plain);
  }
}

// One support point: the field is a single bump, the boundary a sphere around it.
TEST(PointField, OneSupportPoint) {
  Configurations s(1, 3);
  s << 0.2, -0.1, 0.3;
  const Model model(FeatureMap::jointScaling(JointLimits::unitBox(3)),
                    {KernelType::RationalQuadratic, 20, 3, 0}, s,
                    Eigen::VectorXd::Constant(1, 1.0));
  const auto tabulated = model.withPointField();
  const Configurations q = test::uniformPoints(5000, 3, 405);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    ASSERT_EQ(tabulated->inCollision(q.row(i).data()), model.score(q.row(i).data()) > 0);
  }
  // A lone positive weight: every configuration scores above 0, and the grids say so.
  EXPECT_EQ(fieldSign(*tabulated, s.row(0).data()), 1);
}

// Queries beyond the box that the samples reached are left to the full sum.
TEST(PointField, QueriesOutsideTheGridsAreLeftToTheFullSum) {
  const auto model = pointTermModel(3, 800, KernelType::RationalQuadratic, 10, 1);
  PointFieldOptions options;
  options.samples = 1;  // a box of two cells around one configuration
  const auto tabulated = model->withPointField(options);
  const PointField::Grid& grid = tabulated->pointField()->grids()[0];
  for (int a = 0; a < 3; ++a) EXPECT_EQ(grid.cells[a], 2u);
  const Configurations q = test::uniformPoints(2000, 3, 406);
  std::size_t outside = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    ASSERT_EQ(tabulated->inCollision(q.row(i).data()), model->score(q.row(i).data()) > 0);
    outside += fieldSign(*tabulated, q.row(i).data()) == 0;
  }
  EXPECT_GT(outside, 1900u);
}

TEST(PointField, RefusesModelsItCannotTabulateAndBadOptions) {
  const Configurations s = test::uniformPoints(5, 6, 407);
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(5, -1, 1);
  const FeatureMap map = FeatureMap::jointScaling(JointLimits::unitBox(6));
  const auto refuses = [&](const Kernel& kernel, const std::string& words) {
    const Model model(map, kernel, s, w);
    EXPECT_FALSE(model.hasOnlyPointTerms());
    try {
      (void)model.withPointField();
      ADD_FAILURE() << "expected a refusal naming " << words;
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refuses({KernelType::RationalQuadratic, 10, 3, 0.5}, "share 0.5");
  refuses({KernelType::RationalQuadratic, 10, 0, 0}, "one term");
  refuses({KernelType::RationalQuadratic, 10, 2, 0}, "2 features");

  const Model model(map, {KernelType::RationalQuadratic, 10, 3, 0}, s, w);
  EXPECT_TRUE(model.hasOnlyPointTerms());
  const auto refusesOptions = [&](PointFieldOptions options, const std::string& words) {
    try {
      (void)model.withPointField(options);
      ADD_FAILURE() << "expected a refusal naming " << words;
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  PointFieldOptions o;
  o.spacing = 0;
  refusesOptions(o, "spacing");
  o.spacing = std::nan("");
  refusesOptions(o, "spacing");
  o = {};
  o.errorFactor = 0.5;
  refusesOptions(o, "errorFactor");
  o = {};
  o.samples = 0;
  refusesOptions(o, "samples");
  o = {};
  o.spacing = 0.001;  // 2000^3 nodes per term
  refusesOptions(o, "maxNodes");
  o.spacing = 1e-12;  // more nodes than any integer type counts
  refusesOptions(o, "maxNodes");
  o = {};
  o.refinement = 0;
  refusesOptions(o, "refinement");
  o.refinement = 17;
  refusesOptions(o, "refinement");
  o = {};
  o.fineFrom = 1.5;
  refusesOptions(o, "fineFrom");
  o.fineFrom = std::nan("");
  refusesOptions(o, "fineFrom");
}

// Fine blocks are tabulated where the grids' bounds left sampled queries undecided, within their
// budget, and only when the grids leave more than fineFrom of the samples; a field whose blocks
// do not fit its grids, or whose cells' curvatures are out of range, is refused.
TEST(PointField, FineBlocksWithinTheirBudget) {
  const auto model = pointTermModel(6, 1000, KernelType::RationalQuadratic, 10, 10);
  PointFieldOptions options;
  options.spacing = 0.1;
  options.fineFrom = 0;
  options.maxFineNodes = 27 * 40;  // 40 blocks of 2 x 2 x 2 fine cells
  const auto refined = model->withPointField(options);
  const PointField& field = *refined->pointField();
  EXPECT_EQ(field.fineBlockCount(), 40u);
  EXPECT_EQ(field.refinement(), 2u);
  std::size_t blocks = 0;
  for (const PointField::Grid& grid : field.grids()) {
    EXPECT_EQ(grid.fineNodes.size(), grid.fineCells.size() / 8 * 27);
    for (const std::uint32_t block : grid.fineBlock) blocks += block != 0;
  }
  EXPECT_EQ(blocks, 40u);
  options.fineFrom = 1;  // the grids always decide enough
  EXPECT_EQ(model->withPointField(options)->pointField()->fineBlockCount(), 0u);

  std::vector<PointField::Grid> grids = field.grids();
  for (std::uint32_t& block : grids[0].fineBlock) {
    if (block != 0) block = 1000;
  }
  try {
    const PointField broken(grids, field.roundingFloor(), field.spacing(), field.refinement());
    ADD_FAILURE() << "expected a refusal";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("fine blocks"), std::string::npos) << e.what();
  }
  grids = field.grids();
  grids[0].cellTable[0].exponent = -127;
  try {
    const PointField broken(grids, field.roundingFloor(), field.spacing(), field.refinement());
    ADD_FAILURE() << "expected a refusal";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("exponent -127"), std::string::npos) << e.what();
  }
}

// The field is given where it pays: point terms only and enough support points.
TEST(PointField, FastestAnswersTabulateLargeModelsOfPointTermsOnly) {
  // Random labels in 12 dimensions: most points become support points.
  const auto large = pointTermModel(12, 600, KernelType::RationalQuadratic, 10, 1);
  ASSERT_GE(large->supportCount(), kPointFieldMinSupport);
  const auto tabulated = withFastestAnswers(large);
  ASSERT_NE(tabulated->pointField(), nullptr);
  EXPECT_EQ(tabulated->pointField()->answers(), FieldAnswers::Estimate);
  EXPECT_EQ(withFastestAnswers(tabulated), tabulated);  // already tabulated: itself
  const Configurations s = test::uniformPoints(kPointFieldMinSupport - 1, 6, 409);
  const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(s.rows(), -1, 1);
  const FeatureMap map = FeatureMap::jointScaling(JointLimits::unitBox(6));
  const auto small =
      std::make_shared<const Model>(map, Kernel{KernelType::RationalQuadratic, 10, 3, 0}, s, w);
  EXPECT_EQ(withFastestAnswers(small), small);
  const Configurations s2 = test::uniformPoints(kPointFieldMinSupport, 6, 410);
  const auto whole =
      std::make_shared<const Model>(map, Kernel{KernelType::RationalQuadratic, 10, 3, 0.5}, s2,
                                    Eigen::VectorXd::LinSpaced(s2.rows(), -1, 1));
  EXPECT_EQ(withFastestAnswers(whole), whole);
  EXPECT_EQ(withFastestAnswers(nullptr), nullptr);
}

// A field is part of an immutable model: many threads answer from it at once.
TEST(PointField, ThreadsQueryOneFieldAtOnce) {
  PointFieldOptions options;
  options.fineFrom = 0;  // with fine blocks
  const auto tabulated =
      pointTermModel(6, 800, KernelType::RationalQuadratic, 10, 1)->withPointField(options);
  const Configurations q = test::uniformPoints(4000, 6, 408);
  std::vector<char> expected(4000);
  for (Eigen::Index i = 0; i < q.rows(); ++i) expected[i] = tabulated->inCollision(q.row(i).data());
  std::array<std::size_t, 4> wrong{};
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < wrong.size(); ++t) {
    threads.emplace_back([&, t] {
      for (Eigen::Index i = 0; i < q.rows(); ++i) {
        wrong[t] += tabulated->inCollision(q.row(i).data()) != static_cast<bool>(expected[i]);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (const std::size_t w : wrong) EXPECT_EQ(w, 0u);
}

}  // namespace
}  // namespace fastron
