#include "fastron/core/model_checker.h"

#include <gtest/gtest.h>

#include "fastron/core/error.h"
#include "fastron/core/trainer.h"
#include "test_worlds.h"

namespace fastron {
namespace {

std::shared_ptr<const Model> ballModel(std::uint64_t seed) {
  const test::BallWorld world = test::BallWorld::random(2, 3, 0.3, seed);
  TrainParams p;
  p.kernel.gamma = 10;
  Trainer trainer(JointLimits::unitBox(2), p);
  const Configurations q = test::uniformPoints(1500, 2, seed + 1);
  trainer.addPoints(q, world.label(q));
  trainer.update();
  return trainer.model();
}

// A model as a checker answers as the model does, one at a time and as a batch.
TEST(ModelChecker, AnswersAsItsModel) {
  const auto model = ballModel(1);
  const ModelChecker checker(model, "balls model");
  EXPECT_EQ(checker.name(), "balls model");
  EXPECT_EQ(checker.dof(), 2u);
  const Configurations q = test::uniformPoints(500, 2, 3);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    EXPECT_EQ(checker.inCollision({q.row(i).data(), 2}), model->inCollision(q.row(i).data()));
  }
  EXPECT_EQ(checker.firstInCollision(q.data(), 500), model->firstInCollision(q.data(), 500));
  // The Eigen overloads answer as the raw-pointer ones and refuse a wrong column count.
  EXPECT_EQ(checker.firstInCollision(q), checker.firstInCollision(q.data(), 500));
  EXPECT_EQ(model->firstInCollision(q), model->firstInCollision(q.data(), 500));
  const Configurations three = Configurations::Zero(4, 3);
  EXPECT_THROW(checker.firstInCollision(three), InvalidArgument);
  EXPECT_THROW(model->firstInCollision(three), InvalidArgument);
  EXPECT_THROW(ModelChecker(nullptr), InvalidArgument);
}

// Any of two models: in collision where either says so, and a run's first collision is the
// earlier of the two.
TEST(AnyOfChecker, CollidesWhereAnyCollides) {
  const auto a = std::make_shared<ModelChecker>(ballModel(1), "a");
  const auto b = std::make_shared<ModelChecker>(ballModel(7), "b");
  const AnyOfChecker any({a, b});
  EXPECT_EQ(any.name(), "a+b");
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const Configurations q = test::uniformPoints(1 + seed % 25, 2, 50 + seed);
    const auto n = static_cast<std::size_t>(q.rows());
    std::size_t expected = n;
    for (std::size_t i = 0; i < n; ++i) {
      const double* row = q.row(static_cast<Eigen::Index>(i)).data();
      const bool hit = a->inCollision({row, 2}) || b->inCollision({row, 2});
      EXPECT_EQ(any.inCollision({row, 2}), hit);
      if (hit && expected == n) expected = i;
    }
    EXPECT_EQ(any.firstInCollision(q.data(), n), expected) << "seed " << seed;
  }
}

TEST(AnyOfChecker, RefusesBadCheckers) {
  const auto a = std::make_shared<ModelChecker>(ballModel(1));
  const auto three =
      std::make_shared<FunctionChecker>("three", 3, [](const double*) { return false; });
  EXPECT_THROW(AnyOfChecker({}), InvalidArgument);
  EXPECT_THROW(AnyOfChecker({a, nullptr}), InvalidArgument);
  EXPECT_THROW(AnyOfChecker({a, three}), InvalidArgument);
}

// All of two models: in collision only where both say so, a run's first collision is the first
// state both call colliding, and the later checker is asked only about what the first calls
// colliding (the optimistic hybrid's economy).
TEST(AllOfChecker, CollidesWhereAllCollideAndAsksTheLaterOnlyAboutCollisions) {
  const auto a = std::make_shared<ModelChecker>(ballModel(1), "a");
  const auto model = ballModel(7);
  const auto b = std::make_shared<FunctionChecker>(
      "b", 2, [model](const double* q) { return model->inCollision(q); });
  const AllOfChecker all({a, b});
  EXPECT_EQ(all.name(), "a&b");
  EXPECT_TRUE(all.answersFromAModel());
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const Configurations q = test::uniformPoints(1 + seed % 25, 2, 50 + seed);
    const auto n = static_cast<std::size_t>(q.rows());
    std::size_t expected = n, firstCalledColliding = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double* row = q.row(static_cast<Eigen::Index>(i)).data();
      const bool aHit = a->inCollision({row, 2});
      const bool hit = aHit && b->inCollision({row, 2});
      EXPECT_EQ(all.inCollision({row, 2}), hit);
      if (expected == n && aHit) ++firstCalledColliding;
      if (hit && expected == n) expected = i;
    }
    b->resetCallCount();
    EXPECT_EQ(all.firstInCollision(q.data(), n), expected) << "seed " << seed;
    EXPECT_EQ(b->callCount(), firstCalledColliding) << "seed " << seed;
  }
  const auto three =
      std::make_shared<FunctionChecker>("three", 3, [](const double*) { return false; });
  EXPECT_THROW(AllOfChecker({}), InvalidArgument);
  EXPECT_THROW(AllOfChecker({a, nullptr}), InvalidArgument);
  EXPECT_THROW(AllOfChecker({a, three}), InvalidArgument);
}

}  // namespace
}  // namespace fastron
