// The model's collision cost, its OMPL objective, trajectory optimisation and gradient repair
// (issue 53), on a point robot in [-1, 1]^2 around a disk, checked against code independent of
// the optimiser's own checks.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/util/Console.h>

#include <cmath>
#include <memory>

#include "fastron/core/error.h"
#include "fastron/planning/collision_cost.h"
#include "fastron/planning/ompl_adapters.h"
#include "fastron/planning/planner.h"
#include "fastron/planning/trajectory_optimization.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/proxy_collision_detector.h"
#include "finite_differences.h"
#include "temp_dir.h"

namespace fastron {
namespace trajectory_test {

using ::testing::HasSubstr;

// A disk of radius 0.35 about (0, 0.05).
bool inDisk(const double* q) {
  return q[0] * q[0] + (q[1] - 0.05) * (q[1] - 0.05) < 0.35 * 0.35;
}

std::shared_ptr<const CollisionChecker> diskChecker() {
  return std::make_shared<FunctionChecker>("disk", 2, inDisk);
}

Eigen::VectorXd vec(double x, double y) {
  return Eigen::Vector2d(x, y);
}

const Eigen::VectorXd kStart = vec(-0.8, 0.0);
const Eigen::VectorXd kGoal = vec(0.8, 0.0);

/// Every state of every edge at `resolution`, and the waypoints, outside the disk: apart from
/// checkPath on purpose.
bool pathMissesTheDisk(const JointPath& path, double resolution) {
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const auto n = static_cast<int>(std::ceil((path[k + 1] - path[k]).norm() / resolution));
    for (int i = 0; i <= std::max(n, 1); ++i) {
      const double s = std::min(1.0, static_cast<double>(i) / std::max(n, 1));
      const Eigen::VectorXd q = (1 - s) * path[k] + s * path[k + 1];
      if (inDisk(q.data())) return false;
    }
  }
  return !path.empty();
}

ProxyParams diskParams() {
  ProxyParams params;
  params.train = {.kernel = {.gamma = 30}, .beta = 10};
  params.calibrationSamples = 0;
  return params;
}

class Trajectory : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ompl::msg::noOutputHandler();
    proxy_ = std::make_unique<ProxyCollisionDetector>(diskChecker(), JointLimits::unitBox(2),
                                                      diskParams());
    proxy_->initialize(2000);
  }
  static void TearDownTestSuite() { proxy_.reset(); }
  static std::shared_ptr<const Model> model() { return proxy_->model(); }
  static std::unique_ptr<ProxyCollisionDetector> proxy_;
};
std::unique_ptr<ProxyCollisionDetector> Trajectory::proxy_;

TEST_F(Trajectory, ThePathCostIsTheTrapezoidIntegralOfTheStateCostAndItsGradientIsExact) {
  const Model& m = *model();
  const double margin = 0.5;
  Configurations path(5, 2);
  path << -0.8, 0.0, -0.3, 0.1, 0.0, 0.2, 0.35, 0.05, 0.8, 0.0;
  const PathCollisionCost cost = pathCollisionCost(m, path, margin);
  double integral = 0;
  for (Eigen::Index t = 0; t + 1 < path.rows(); ++t) {
    const double a = stateCollisionCost(m, path.row(t).transpose(), margin).cost;
    const double b = stateCollisionCost(m, path.row(t + 1).transpose(), margin).cost;
    integral += 0.5 * (a + b) * (path.row(t + 1) - path.row(t)).norm();
  }
  ASSERT_GT(integral, 0) << "the path must cross the disk";
  EXPECT_NEAR(cost.cost, integral, 1e-9 * integral);
  // Central differences of the whole cost with respect to every value of every waypoint (the
  // scores are summed in float: a step of 1e-3 keeps their rounding below the tolerance).
  Eigen::Map<Eigen::VectorXd> flat(path.data(), path.size());
  const auto costAt = [&](const double* values) {
    Configurations moved = Eigen::Map<const Configurations>(values, path.rows(), path.cols());
    return pathCollisionCost(m, moved, margin).cost;
  };
  const Eigen::VectorXd numeric = test::centralDifferences(costAt, flat, 1e-3);
  const Eigen::Map<const Eigen::VectorXd> analytic(cost.gradient.data(), cost.gradient.size());
  for (Eigen::Index i = 0; i < numeric.size(); ++i)
    EXPECT_NEAR(analytic[i], numeric[i], 2e-3 * std::max(1.0, std::abs(numeric[i]))) << i;
  // Where the model scores below -margin the hinge is off: no cost, no gradient.
  const Eigen::VectorXd far = vec(-0.9, -0.9);
  const double f = m.score(far.data());
  ASSERT_LT(f, 0);
  const StateCollisionCost free = stateCollisionCost(m, far, -f / 2);
  EXPECT_EQ(free.cost, 0);
  EXPECT_EQ(free.gradient.norm(), 0);
  EXPECT_GT(stateCollisionCost(m, far, -2 * f).cost, 0);
}

TEST_F(Trajectory, BadCostArgumentsAreRefused) {
  const Model& m = *model();
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] { (void)stateCollisionCost(m, vec(0, 0), -1); }),
              HasSubstr("margin"));
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [&] { (void)pathCollisionCost(m, Configurations(1, 2), 0); }),
              HasSubstr("at least two waypoints"));
  EXPECT_THROW((void)pathCollisionCost(m, Configurations::Zero(3, 3), 0), InvalidArgument);
  EXPECT_THROW((void)stateCollisionCost(m, vec(NAN, 0), 0), InvalidArgument);
}

TEST_F(Trajectory, TheOmplObjectiveIntegratesTheStateCost) {
  const auto si = makeSpaceInformation(model(), JointLimits::unitBox(2), 0.01);
  const double margin = 0.5;
  const ModelCollisionObjective exactEnds(si, model(), margin, false);
  ompl::base::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace());
  a[0] = -0.5;
  a[1] = 0.0;
  b[0] = 0.0;
  b[1] = 0.1;
  const double ca = stateCollisionCost(*model(), vec(-0.5, 0.0), margin).cost;
  const double cb = stateCollisionCost(*model(), vec(0.0, 0.1), margin).cost;
  // The objective scores with Model::score, the cost with scoreGradient: float sums of their
  // own, equal to float precision.
  EXPECT_NEAR(exactEnds.stateCost(b.get()).value(), cb, 1e-5 * std::max(1.0, cb));
  const double trapezoid = 0.5 * (ca + cb) * (vec(0.0, 0.1) - vec(-0.5, 0.0)).norm();
  EXPECT_NEAR(exactEnds.motionCost(a.get(), b.get()).value(), trapezoid,
              1e-5 * std::max(1.0, trapezoid));
  // Length plus a weight of the integral (interpolated at the space's resolution).
  const auto both = lengthAndCollisionObjective(si, model(), 2.0, margin);
  const ModelCollisionObjective interpolated(si, model(), margin);
  EXPECT_NEAR(
      both->motionCost(a.get(), b.get()).value(),
      si->distance(a.get(), b.get()) + 2.0 * interpolated.motionCost(a.get(), b.get()).value(),
      1e-9);
  EXPECT_THROW(lengthAndCollisionObjective(si, model(), -1, margin), InvalidArgument);
  EXPECT_THROW(ModelCollisionObjective(si, nullptr, margin), InvalidArgument);
  const auto three = makeSpaceInformation(
      std::make_shared<FunctionChecker>("none", 3, [](const double*) { return false; }),
      JointLimits::unitBox(3), 0.01);
  EXPECT_THAT(
      test::messageOf<InvalidArgument>([&] { ModelCollisionObjective(three, model(), margin); }),
      HasSubstr("2 joints"));
}

TEST_F(Trajectory, RrtStarPlansWithTheLengthAndCollisionObjective) {
  const auto si = makeSpaceInformation(model(), JointLimits::unitBox(2), 0.02);
  PlannerOptions options{.type = PlannerType::RrtStar};
  const auto planner = makePlanner(si, options);
  const auto problem = makeProblemDefinition(si, kStart, kGoal, PlannerType::RrtStar);
  auto objective = lengthAndCollisionObjective(si, model(), 1.0, 0.5);
  objective->setCostThreshold(objective->infiniteCost());  // stop at the first solution
  problem->setOptimizationObjective(objective);
  planner->setProblemDefinition(problem);
  planner->setup();
  ASSERT_EQ(planner->solve(5.0), ompl::base::PlannerStatus::EXACT_SOLUTION);
  EXPECT_TRUE(std::isfinite(problem->getSolutionPath()->cost(objective).value()));
}

TEST(TrajectoryOptimisation, DensePathsKeepTheirEndsAndSpacing) {
  const JointPath path = densePath({vec(-1, 0), vec(0, 0), vec(0, 0.05)}, 0.1);
  EXPECT_TRUE(path.front().isApprox(vec(-1, 0)));
  EXPECT_TRUE(path.back().isApprox(vec(0, 0.05)));
  EXPECT_EQ(path.size(), 12u);  // 10 pieces, then 1
  for (std::size_t k = 0; k + 1 < path.size(); ++k)
    EXPECT_LE((path[k + 1] - path[k]).norm(), 0.1 + 1e-12);
  EXPECT_GE(straightPath(vec(0, 0), vec(0.01, 0), 0.1).size(), 8u);
  EXPECT_THROW((void)densePath({}, 0.1), InvalidArgument);
  EXPECT_THAT(test::messageOf<InvalidArgument>([] { (void)densePath({vec(0, 0)}, 0); }),
              HasSubstr("spacing"));
  EXPECT_THROW((void)straightPath(vec(0, 0), Eigen::VectorXd::Zero(3), 0.1), InvalidArgument);
}

TEST_F(Trajectory, TheOptimiserPushesAStraightLineOutOfTheDisk) {
  const JointPath line = straightPath(kStart, kGoal, 0.05);
  ASSERT_FALSE(pathMissesTheDisk(line, 0.005));
  const OptimizedTrajectory out =
      optimizeTrajectory(*model(), JointLimits::unitBox(2), line, TrajectoryOptions{});
  ASSERT_TRUE(out.freeOnModel) << out.iterations << " iterations";
  EXPECT_EQ(out.path.size(), line.size());
  EXPECT_TRUE(out.path.front() == kStart && out.path.back() == kGoal) << "the ends do not move";
  EXPECT_LT(out.costs.back(), out.costs.front());
  EXPECT_EQ(out.costs.size(), out.iterations + 1);
  for (const Eigen::VectorXd& q : out.path) EXPECT_LE(q.cwiseAbs().maxCoeff(), 1.0);
  EXPECT_TRUE(pathMissesTheDisk(out.path, 0.005)) << "a margin of 1 clears the true disk";
  EXPECT_LT(pathLength(out.path), 3.0);
}

TEST_F(Trajectory, BadOptimiserInputsAreRefused) {
  const JointLimits box = JointLimits::unitBox(2);
  const JointPath line = straightPath(kStart, kGoal, 0.05);
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [&] { (void)optimizeTrajectory(*model(), box, line, {.maxStep = 0}); }),
              HasSubstr("maxStep"));
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [&] { (void)optimizeTrajectory(*model(), box, line, {.smoothing = 2}); }),
              HasSubstr("smoothing"));
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [&] { (void)optimizeTrajectory(*model(), box, line, {.timeLimit = -1}); }),
              HasSubstr("timeLimit"));
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] {
                (void)optimizeTrajectory(*model(), box, {kStart, kGoal}, {});
              }),
              HasSubstr("three waypoints"));
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] {
                (void)optimizeTrajectory(*model(), box, {kStart, vec(0, 1.5), kGoal}, {});
              }),
              HasSubstr("waypoint 1 is outside the joint limits"));
}

TEST(TrajectoryOptimisation, VerifiedOptimisationLearnsUntilTheExactCheckerAgrees) {
  // The oracle sees a smaller disk: the model's first path grazes the true one, and
  // verification's answers teach it the rest.
  const auto smaller = std::make_shared<FunctionChecker>("smaller disk", 2, [](const double* q) {
    return q[0] * q[0] + (q[1] - 0.05) * (q[1] - 0.05) < 0.2 * 0.2;
  });
  ProxyCollisionDetector proxy(smaller, JointLimits::unitBox(2), diskParams());
  proxy.initialize(2000);
  const VerifiedTrajectory out =
      optimizeVerified(proxy, diskChecker(), kStart, kGoal, 0.01, TrajectoryOptions{});
  ASSERT_EQ(out.status, PlanStatus::Solved) << out.failure;
  EXPECT_TRUE(pathMissesTheDisk(out.path, 0.005));
  EXPECT_GE(out.rounds, 1u);
  EXPECT_FALSE(out.costs.empty());
  const auto ends = optimizeVerified(proxy, diskChecker(), vec(0, 0), kGoal, 0.01, {});
  EXPECT_EQ(ends.status, PlanStatus::InvalidStart);
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [&] { (void)optimizeVerified(proxy, diskChecker(), kStart, kGoal, 0, {}); }),
              HasSubstr("resolution"));
  // A time limit bounds every round and check together: a tiny one stops after the first check.
  const auto bounded = optimizeVerified(proxy, smaller, kStart, kGoal, 0.01, {.timeLimit = 1e-9});
  EXPECT_EQ(bounded.rounds, 1u);
  EXPECT_LE(bounded.iterations, 1u);
}

TEST(TrajectoryOptimisation, GradientRepairReturnsOnlyPathsTheExactCheckerFindsFree) {
  // The oracle's disk is 0.05 smaller than the true one: the model's straight line just over it
  // crosses the true disk's rim, the graze that gradient repair is for. Whether a push frees it
  // depends on what the model learns (docs/trajectories.md); what it returns is always free.
  const auto smaller = std::make_shared<FunctionChecker>("smaller disk", 2, [](const double* q) {
    return q[0] * q[0] + (q[1] - 0.05) * (q[1] - 0.05) < 0.3 * 0.3;
  });
  const Eigen::VectorXd start = vec(-0.8, 0.38), goal = vec(0.8, 0.38);
  ASSERT_FALSE(pathMissesTheDisk({start, goal}, 0.005));
  std::size_t stretches = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    ProxyParams params = diskParams();
    params.seed = seed;
    ProxyCollisionDetector proxy(smaller, JointLimits::unitBox(2), params);
    proxy.initialize(1500);
    const PlannerOptions options{
        .resolution = 0.01, .timeLimit = 5, .verify = {.gradientRepair = true}};
    seedPlanners(seed, 0);
    const VerifiedPlan plan =
        planVerifiedLearning(proxy, diskChecker(), JointLimits::unitBox(2), start, goal, options);
    ASSERT_TRUE(plan.solved()) << plan.failure;
    EXPECT_TRUE(pathMissesTheDisk(plan.path, 0.005)) << "seed " << seed;
    EXPECT_LE(plan.gradientRepairs, plan.invalidStretches);
    stretches += plan.invalidStretches;
  }
  EXPECT_GT(stretches, 0u) << "the model's paths graze the rim";
}

}  // namespace trajectory_test
}  // namespace fastron
