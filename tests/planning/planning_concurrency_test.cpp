// Planning on model snapshots while a background thread keeps updating the model: every plan
// sees one consistent model and ends valid under the exact checker. Runs under ThreadSanitizer.

#include <gtest/gtest.h>
#include <ompl/util/Console.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

#include "fastron/planning/trajectory_optimization.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron {
namespace {

TEST(PlanningConcurrency, PlansOnSnapshotsWhileTheModelUpdates) {
  ompl::msg::noOutputHandler();
  // A wall with a gap whose height the background thread's world keeps changing.
  std::atomic<double> gapBottom{0.4};
  const auto moving = std::make_shared<const FunctionChecker>(
      "moving wall", 2,
      [&](const double* q) { return std::abs(q[0]) < 0.1 && q[1] < gapBottom.load(); });
  const JointLimits limits = JointLimits::unitBox(2);
  ProxyCollisionDetector proxy(moving, limits,
                               {.train = {.kernel = {.gamma = 30}, .beta = 10},
                                .activeLearning = {.maxSamples = 200},
                                .seed = 3,
                                .labelThreads = 1});
  proxy.initialize(1500);
  std::atomic<int> steps{0};
  proxy.startBackground([&](const StepReport&) { steps.fetch_add(1); });

  Eigen::VectorXd start(2), goal(2);
  start << -0.8, -0.8;
  goal << 0.8, -0.8;
  const PlannerOptions options{.resolution = 0.01, .timeLimit = 2};
#ifdef FASTRON_SANITIZED
  constexpr int kPlans = 6;
#else
  constexpr int kPlans = 30;
#endif
  // At least kPlans plans, and on until the background thread has published several models
  // (10 s at most, however loaded the machine).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (int i = 0; i < kPlans || (steps.load() < 3 && std::chrono::steady_clock::now() < deadline);
       ++i) {
    // The exact world each plan is verified against is fixed for that plan.
    const double bottom = 0.3 + 0.02 * (i % 5);
    gapBottom.store(bottom);
    const auto exact = std::make_shared<const FunctionChecker>(
        "wall", 2, [bottom](const double* q) { return std::abs(q[0]) < 0.1 && q[1] < bottom; });
    const VerifiedPlan plan = planVerified(proxy.model(), exact, limits, start, goal, options);
    ASSERT_TRUE(plan.solved()) << plan.failure;
    EXPECT_TRUE(checkPath(*exact, plan.path, options.resolution).valid());
  }
  proxy.stopBackground();
  EXPECT_GE(steps.load(), 3);
}

// Gradients and trajectory optimisation on snapshots from several threads while the background
// thread publishes new models: a snapshot answers the same every time, whoever asks.
TEST(PlanningConcurrency, GradientsAndOptimisationOnSnapshotsWhileTheModelUpdates) {
  std::atomic<double> radius{0.3};
  const auto moving = std::make_shared<const FunctionChecker>(
      "moving disk", 2,
      [&](const double* q) { return q[0] * q[0] + q[1] * q[1] < radius.load() * radius.load(); });
  const JointLimits limits = JointLimits::unitBox(2);
  ProxyCollisionDetector proxy(moving, limits,
                               {.train = {.kernel = {.gamma = 30}, .beta = 10},
                                .activeLearning = {.maxSamples = 200},
                                .seed = 5,
                                .labelThreads = 1});
  proxy.initialize(1500);
  std::atomic<int> steps{0};
  proxy.startBackground([&](const StepReport&) {
    steps.fetch_add(1);
    radius.store(0.25 + 0.01 * (steps.load() % 5));
  });
  Eigen::VectorXd start(2), goal(2);
  start << -0.8, 0.02;
  goal << 0.8, 0.0;
  const JointPath line = straightPath(start, goal, 0.05);
  std::atomic<int> failures{0};
  const auto work = [&](int rounds) {
    for (int i = 0; i < rounds; ++i) {
      const std::shared_ptr<const Model> snapshot = proxy.model();
      const Configurations q = statesAlongPath(line, 0.1);
      const Model::ScoreGradients batch = snapshot->scoreGradients(q);
      const Model::ScoreGradients again = snapshot->scoreGradients(q);
      if (batch.gradients != again.gradients || batch.scores != again.scores) failures.fetch_add(1);
      const OptimizedTrajectory a = optimizeTrajectory(*snapshot, limits, line, {});
      const OptimizedTrajectory b = optimizeTrajectory(*snapshot, limits, line, {});
      if (a.path != b.path) failures.fetch_add(1);
    }
  };
#ifdef FASTRON_SANITIZED
  constexpr int kRounds = 3;
#else
  constexpr int kRounds = 20;
#endif
  std::thread other(work, kRounds);
  work(kRounds);
  other.join();
  proxy.stopBackground();
  EXPECT_EQ(failures.load(), 0);
}

}  // namespace
}  // namespace fastron
