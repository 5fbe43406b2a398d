// RecordingChecker keeps exactly the answers its inner checker gave, also for runs of
// configurations (the batch path verification uses); CountedChecker counts them.

#include "fastron/core/recording_checker.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "fastron/core/error.h"

namespace fastron {
namespace {

TEST(RecordingChecker, RecordsEveryAnsweredConfigurationOnceInOrder) {
  // Collides where the first value exceeds 0.5.
  const auto inner =
      std::make_shared<FunctionChecker>("half", 2, [](const double* q) { return q[0] > 0.5; });
  RecordingChecker recorder(inner);
  EXPECT_EQ(recorder.name(), "half");
  EXPECT_TRUE(recorder.inCollision(std::vector<double>{0.9, 0.0}));
  // A run stops at its first collision: rows 0 and 1 answered, row 2 never asked.
  const std::vector<double> run{0.1, 1.0, 0.7, 2.0, 0.2, 3.0};
  EXPECT_EQ(recorder.firstInCollision(run.data(), 3), 1u);
  const std::vector<double> free{0.1, 4.0, 0.2, 5.0};
  EXPECT_EQ(recorder.firstInCollision(free.data(), 2), 2u);
  EXPECT_EQ(recorder.recorded(), 5u);
  EXPECT_EQ(inner->callCount(), 5u);
  const Dataset answers = recorder.take();
  ASSERT_EQ(answers.size(), 5u);
  const std::vector<double> firsts{0.9, 0.1, 0.7, 0.1, 0.2};
  const std::vector<std::int8_t> labels{1, -1, 1, -1, -1};
  for (Eigen::Index i = 0; i < 5; ++i) {
    EXPECT_EQ(answers.points(i, 0), firsts[static_cast<std::size_t>(i)]) << "row " << i;
    EXPECT_EQ(answers.labels[static_cast<std::size_t>(i)], labels[static_cast<std::size_t>(i)]);
  }
  EXPECT_EQ(recorder.recorded(), 0u) << "take() empties the record";
  EXPECT_THROW(RecordingChecker(nullptr), InvalidArgument);
}

// inCollisionEach (the labelling's path) answers every row, so every row is recorded.
TEST(RecordingChecker, RecordsEveryRowOfARunAnsweredEach) {
  const auto inner =
      std::make_shared<FunctionChecker>("half", 2, [](const double* q) { return q[0] > 0.5; });
  RecordingChecker recorder(inner);
  const std::vector<double> run{0.1, 1.0, 0.7, 2.0, 0.2, 3.0};
  std::uint8_t hits[3] = {9, 9, 9};
  recorder.inCollisionEach(run.data(), 3, hits);
  EXPECT_EQ(hits[0], 0);
  EXPECT_EQ(hits[1], 1);
  EXPECT_EQ(hits[2], 0);
  EXPECT_EQ(inner->callCount(), 3u);
  EXPECT_EQ(recorder.callCount(), 3u);
  const Dataset answers = recorder.take();
  ASSERT_EQ(answers.size(), 3u);
  EXPECT_EQ(answers.labels, (Labels{-1, 1, -1}));
  EXPECT_EQ(answers.points(2, 1), 3.0);
}

// CountedChecker answers as its inner checker on every path and counts only what was asked
// through it, as the inner checker counts it; another user of the inner checker is not counted.
TEST(CountedChecker, CountsWhatWasAskedThroughIt) {
  const auto inner =
      std::make_shared<FunctionChecker>("half", 2, [](const double* q) { return q[0] > 0.5; });
  const CountedChecker counted(inner);
  EXPECT_EQ(counted.name(), "half");
  EXPECT_EQ(counted.dof(), 2u);
  EXPECT_FALSE(counted.answersFromAModel());
  EXPECT_TRUE(counted.inCollision(std::vector<double>{0.9, 0.0}));
  const std::vector<double> run{0.1, 1.0, 0.7, 2.0, 0.2, 3.0};
  EXPECT_EQ(counted.firstInCollision(run.data(), 3), 1u);  // rows 0 and 1 asked
  std::uint8_t hits[3] = {9, 9, 9};
  counted.inCollisionEach(run.data(), 3, hits);
  EXPECT_EQ(hits[0], 0);
  EXPECT_EQ(hits[1], 1);
  EXPECT_EQ(hits[2], 0);
  EXPECT_EQ(counted.callCount(), 6u);
  EXPECT_EQ(inner->callCount(), 6u);
  EXPECT_FALSE(inner->inCollision(std::vector<double>{0.1, 0.0}));  // not through it
  EXPECT_EQ(counted.callCount(), 6u);
  EXPECT_THROW(CountedChecker(nullptr), InvalidArgument);
}

}  // namespace
}  // namespace fastron
