// The planning layer: motion discretisation, planners on OMPL, and verify-and-repair, checked
// against exact checkers with code independent of the planner's own checks.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <set>
#include <thread>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/hybrid_checker.h"
#include "fastron/core/model_checker.h"
#include "fastron/core/trainer.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/planning/motion.h"
#include "fastron/planning/ompl_adapters.h"
#include "fastron/planning/parallel_check.h"
#include "fastron/planning/planner.h"
#include "fastron/planning/state_answers.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/labelling.h"
#include "fastron/proxy/proxy_collision_detector.h"
#include "temp_dir.h"
#include "test_worlds.h"

namespace fastron {
namespace {

using test::messageOf;
using ::testing::HasSubstr;

// A point robot in [-1, 1]^2 and a wall x in [-0.1, 0.1], y < 0.5, with a gap above it.
bool inWall(const double* q) {
  return std::abs(q[0]) < 0.1 && q[1] < 0.5;
}

std::shared_ptr<const CollisionChecker> wallChecker() {
  return std::make_shared<FunctionChecker>("wall", 2, inWall);
}

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  std::copy(values.begin(), values.end(), v.begin());
  return v;
}

const Eigen::VectorXd kStart = vec({-0.8, -0.8});
const Eigen::VectorXd kGoal = vec({0.8, -0.8});

/// True when every waypoint of the path, and every state a + (b - a) i / n (n = ceil(|b - a| /
/// resolution)) of every edge, is free under `collides`: written apart from checkPath on purpose.
template <class Collides>
bool pathIsFree(const JointPath& path, double resolution, const Collides& collides) {
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const double length = (path[k + 1] - path[k]).norm();
    const auto n = std::max<long>(1, static_cast<long>(std::ceil(length / resolution)));
    for (long i = 0; i <= n; ++i) {
      // The last state is the waypoint itself, not a + (b - a) * 1, which can round across a
      // wall's face that the waypoint lies on.
      const Eigen::VectorXd q =
          i == n ? path[k + 1]
                 : Eigen::VectorXd(path[k] + (path[k + 1] - path[k]) *
                                                 (static_cast<double>(i) / static_cast<double>(n)));
      if (collides(q)) return false;
    }
  }
  return !path.empty();
}

/// The proxies of the learning tests: a narrow kernel for the wall's sharp edges, no calibrated
/// band, and support points not relabelled, so that a model learns only what it is told.
ProxyParams learningProxyParams() {
  ProxyParams params;
  params.train = {.kernel = {.gamma = 30}, .beta = 10};
  params.calibrationSamples = 0;
  params.relabelSupport = false;
  return params;
}

class Planning : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { ompl::msg::noOutputHandler(); }  // tests print nothing of OMPL's
};

TEST(Motion, SegmentCountKeepsEveryStepWithinTheResolution) {
  EXPECT_EQ(segmentCount(vec({0, 0}), vec({0, 0}), 0.1), 1u);
  EXPECT_EQ(segmentCount(vec({0, 0}), vec({0.3, 0.4}), 0.1), 5u);
  EXPECT_EQ(segmentCount(vec({0, 0}), vec({0.3, 0.4}), 0.099), 6u);
  EXPECT_THROW(segmentCount(vec({0}), vec({1}), 0), InvalidArgument);
  EXPECT_THROW(segmentCount(vec({0}), vec({1}), std::nan("")), InvalidArgument);
}

TEST(Motion, StatesCoverTheMotionOnceInBisectionOrder) {
  for (const std::size_t n : {1u, 2u, 3u, 7u, 8u, 13u, 64u}) {
    std::vector<double> states;
    const double a[] = {0.0};
    const double b[] = {static_cast<double>(n)};
    motionStates(a, b, 1, n, states);
    ASSERT_EQ(states.size(), n);
    EXPECT_EQ(states[0], static_cast<double>(n)) << "the end state comes first";
    if (n >= 4) {  // then the largest power of two below n
      EXPECT_EQ(states[1], std::exp2(std::floor(std::log2(static_cast<double>(n - 1)))));
    }
    const std::set<double> unique(states.begin(), states.end());
    EXPECT_EQ(unique.size(), n);
    EXPECT_EQ(*unique.begin(), 1.0);
  }
}

TEST(Motion, BisectionIndexNamesEachRowsState) {
  for (std::size_t n = 1; n <= 40; ++n) {
    std::vector<double> states;
    const double a[] = {0.0};
    const double b[] = {static_cast<double>(n)};
    motionStates(a, b, 1, n, states);
    std::set<std::size_t> indices;
    for (std::size_t row = 0; row < n; ++row) {
      const std::size_t i = bisectionIndex(n, row);
      double state = 0;
      motionState(a, b, 1, i, n, &state);
      EXPECT_EQ(state, states[row]) << n << " row " << row;  // the same arithmetic, bit for bit
      indices.insert(i);
    }
    EXPECT_EQ(indices.size(), n);
    EXPECT_EQ(*indices.begin(), 1u);
    EXPECT_EQ(*indices.rbegin(), n);
  }
}

TEST(Motion, TheEndStateIsTheEndItself) {
  // -0.8 + (0.35 - -0.8) * 1 rounds to 0.34999999999999987: the end state must be b bit for bit,
  // or a validator's remembered answer about b would be one about another configuration.
  const double a[] = {-0.8, 0.7};
  const double b[] = {0.35, 0.1};
  std::vector<double> states;
  motionStates(a, b, 2, 5, states);
  EXPECT_EQ(states[0], b[0]);
  EXPECT_EQ(states[1], b[1]);
}

TEST(StateAnswers, RemembersAnswersByExactValues) {
  StateAnswers answers(2);
  const double q[] = {0.25, -1.5};
  EXPECT_FALSE(answers.find(q).has_value());
  answers.remember(q, true);
  EXPECT_EQ(answers.find(q), std::optional<bool>(true));
  answers.remember(q, false);
  EXPECT_EQ(answers.find(q), std::optional<bool>(false));
  const double near[] = {std::nextafter(0.25, 1.0), -1.5};
  EXPECT_FALSE(answers.find(near).has_value()) << "one ulp away is another configuration";
}

TEST(StateAnswers, ANewAnswerReplacesTheOneInItsSlot) {
  StateAnswers answers(1, 1);  // one slot: every configuration maps to it
  const double p[] = {1.0}, q[] = {2.0};
  answers.remember(p, true);
  answers.remember(q, false);
  EXPECT_FALSE(answers.find(p).has_value());
  EXPECT_EQ(answers.find(q), std::optional<bool>(false));
  EXPECT_THROW(StateAnswers(0), InvalidArgument);
  EXPECT_THROW(StateAnswers(2, 0), InvalidArgument);
}

// The states along a path are those a check at that resolution looks at (checkPath's edges cut
// by segmentCount, motionStates' values), in the path's order, no step longer than the resolution.
TEST(Motion, StatesAlongAPathAreTheCheckedStatesInOrder) {
  const JointPath path{vec({0, 0}), vec({0.3, 0.4}), vec({0.3, 0.4}), vec({-0.2, 0.4})};
  const double resolution = 0.09;
  const Configurations states = statesAlongPath(path, resolution);
  ASSERT_EQ(states.rows(), 1 + 6 + 1 + 6);  // ceil(0.5 / 0.09) = 6, a zero-length edge 1
  EXPECT_EQ(edgeSegments(path, resolution), (std::vector<std::size_t>{6, 1, 6}));
  EXPECT_EQ(Eigen::VectorXd(states.row(0).transpose()), path.front());
  EXPECT_EQ(Eigen::VectorXd(states.row(states.rows() - 1).transpose()), path.back());
  for (Eigen::Index i = 1; i < states.rows(); ++i) {
    EXPECT_LE((states.row(i) - states.row(i - 1)).norm(), resolution + 1e-12) << "state " << i;
  }
  std::vector<double> edge;
  motionStates(path[0].data(), path[1].data(), 2, 6, edge);
  std::set<std::pair<double, double>> checked, along;
  for (std::size_t k = 0; k < edge.size(); k += 2) checked.insert({edge[k], edge[k + 1]});
  for (Eigen::Index i = 1; i <= 6; ++i) along.insert({states(i, 0), states(i, 1)});
  EXPECT_EQ(along, checked) << "the same numbers as the verification checks";
  EXPECT_EQ(statesAlongPath({}, resolution).rows(), 0);
  EXPECT_THROW(statesAlongPath({vec({0, 0}), vec({0})}, resolution), InvalidArgument);
}

class PathFiles : public test::TempDir {};

TEST_F(PathFiles, ReadsWhatWritePathCsvWrites) {
  const JointPath path{vec({0.1, -2.5}), vec({1.0 / 3.0, 1e-17}), vec({3.0, 0.0})};
  writePathCsv(path, {"a", "b"}, this->path("p.csv"));
  EXPECT_EQ(readPathCsv(this->path("p.csv"), {"a", "b"}), path);
  write("bare.csv", "0.5, 1\n\n-1,2\r\n");
  EXPECT_EQ(readPathCsv(this->path("bare.csv"), {"a", "b"}),
            (JointPath{vec({0.5, 1}), vec({-1, 2})}));
}

TEST_F(PathFiles, BadPathFilesNameTheFileLineAndColumn) {
  const auto error = [&](const std::string& text) {
    write("p.csv", text);
    return messageOf<FileError>([&] { readPathCsv(path("p.csv"), {"a", "b"}); });
  };
  EXPECT_THAT(error("a,c\n0,0\n"),
              HasSubstr("p.csv:1: column 2 is 'c', but the robot's joint 2 is 'b'"));
  EXPECT_THAT(error("a\n0\n"),
              HasSubstr("p.csv:1: column 2 is 'nothing', but the robot's joint 2 is 'b'"));
  EXPECT_THAT(error("a,b,c\n0,0,0\n"),
              HasSubstr("column 3 is 'c', but the robot's joint 3 is 'no joint'"));
  EXPECT_THAT(error("\n0,0,0\n"), HasSubstr("p.csv:2: 3 columns, but the robot has 2 joints"));
  EXPECT_THAT(error("a,b\n0,0\n1\n"), HasSubstr("p.csv:3: 1 columns, expected 2"));
  EXPECT_THAT(error("a,b\n0,x\n"), HasSubstr("p.csv:2: column 2: 'x' is not a number"));
  EXPECT_THAT(error("a,b\n0,nan\n"), HasSubstr("p.csv:2: column 2: value is not finite"));
  EXPECT_THAT(error("a,b\n"), HasSubstr("p.csv: no waypoints"));
  EXPECT_THAT(error(""), HasSubstr("p.csv: no waypoints"));
  EXPECT_THAT(messageOf<FileError>([&] { readPathCsv(path("absent.csv"), {"a"}); }),
              HasSubstr("absent.csv: cannot open path file"));
}

TEST(Motion, CheckPathFindsInvalidWaypointsAndEdges) {
  const auto wall = wallChecker();
  const JointPath path{kStart, vec({-0.5, 0.0}), vec({0.0, 0.0}), vec({0.5, 0.9}), kGoal};
  const PathCheck check = checkPath(*wall, path, 0.01);
  EXPECT_THAT(check.invalidWaypoints, ::testing::ElementsAre(2u));
  EXPECT_THAT(check.invalidEdges, ::testing::ElementsAre(1u, 2u));
  EXPECT_FALSE(check.valid());
  EXPECT_FALSE(checkPath(*wall, {}, 0.01).valid());
  EXPECT_TRUE(checkPath(*wall, {kStart, vec({-0.5, 0.9}), vec({0.5, 0.9}), kGoal}, 0.01).valid());
  EXPECT_THROW(checkPath(*wall, {vec({0, 0, 0})}, 0.01), InvalidArgument);
}

// The parallel, bisection-ordered check gives checkPath's answer: on the wall, and on random
// Baxter paths among three boxes (FCL, many invalid stretches), with 1, 2 and 3 threads.
TEST(Motion, ParallelCheckEqualsTheSerialCheck) {
  const auto wall = wallChecker();
  const JointPath wallPath{kStart, vec({-0.5, 0.0}), vec({0.0, 0.0}), vec({0.5, 0.9}), kGoal};
  for (const unsigned threads : {0u, 1u, 2u, 3u}) {
    const PathCheck check = checkPathParallel(*wall, wallPath, 0.001, threads);
    EXPECT_THAT(check.invalidWaypoints, ::testing::ElementsAre(2u));
    EXPECT_THAT(check.invalidEdges, ::testing::ElementsAre(1u, 2u));
  }
  EXPECT_FALSE(checkPathParallel(*wall, {}, 0.01).valid());
  EXPECT_THROW(checkPathParallel(*wall, {vec({0, 0, 0})}, 0.01), InvalidArgument);

  const Robot baxter = loadRobot("baxter");
  const FclChecker fcl(baxter, loadScene(dataDirectory() / "scenes" / "baxter_three_boxes.yaml"));
  Rng rng(21);
  std::size_t invalidEdges = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Configurations waypoints = uniformConfigurations(baxter.limits(), 2 + trial % 6, rng);
    JointPath path;
    for (Eigen::Index i = 0; i < waypoints.rows(); ++i) path.emplace_back(waypoints.row(i));
    const PathCheck serial = checkPath(fcl, path, 0.05);
    invalidEdges += serial.invalidEdges.size();
    for (const unsigned threads : {0u, 1u, 2u, 3u}) {
      const PathCheck parallel = checkPathParallel(fcl, path, 0.05, threads);
      EXPECT_EQ(parallel.invalidWaypoints, serial.invalidWaypoints) << "trial " << trial;
      EXPECT_EQ(parallel.invalidEdges, serial.invalidEdges) << "trial " << trial;
    }
  }
  EXPECT_GT(invalidEdges, 10u) << "the test needs colliding edges";
}

// A planner handed whole motions (a checker that proves them free) gets the answers it would get
// state by state: with the same seed, the same path, valid under a dense check at a finer step.
TEST(Motion, PlannersGetTheSameAnswersFromWholeMotions) {
  const Robot baxter = loadRobot("baxter");
  const Scene scene = loadScene(dataDirectory() / "scenes" / "baxter_three_boxes.yaml");
  const auto certified =
      std::make_shared<const FclChecker>(baxter, scene, CheckerOptions{.selfCollision = true});
  const auto dense = std::make_shared<const FclChecker>(
      baxter, scene, CheckerOptions{.selfCollision = true, .proveMotionsFree = false});
  ASSERT_TRUE(certified->provesMotionsFree());
  ASSERT_FALSE(dense->provesMotionsFree());
  Rng rng(8);
  const Configurations q = uniformConfigurations(baxter.limits(), 200, rng);
  std::vector<Eigen::VectorXd> free;
  for (Eigen::Index i = 0; i < q.rows() && free.size() < 8; ++i) {
    if (!dense->inCollision(std::span<const double>(q.row(i).data(), baxter.dof())))
      free.emplace_back(q.row(i).transpose());
  }
  ASSERT_EQ(free.size(), 8u);
  const PlannerOptions options{.resolution = 0.03, .timeLimit = 10, .simplifyTime = 0};
  for (std::size_t i = 0; i + 1 < free.size(); i += 2) {
    seedPlanners(4, i);
    const PlanResult onCertified =
        planMotion(certified, baxter.limits(), free[i], free[i + 1], options);
    seedPlanners(4, i);
    const PlanResult onDense = planMotion(dense, baxter.limits(), free[i], free[i + 1], options);
    ASSERT_TRUE(onCertified.solved()) << "query " << i;
    ASSERT_EQ(onCertified.path.size(), onDense.path.size()) << "query " << i;
    for (std::size_t w = 0; w < onDense.path.size(); ++w)
      EXPECT_TRUE(onCertified.path[w].isApprox(onDense.path[w], 0)) << "query " << i;
    EXPECT_TRUE(checkPath(*dense, onCertified.path, 0.01).valid()) << "query " << i;
  }
}

// threads = 0 decides by the time the first states took: a path whose checks add up to tens of
// milliseconds (50 us a state, about 800 states) is shared with a worker thread, and a path of
// cheap checks (about 80 states at well under a microsecond) stays on the calling thread. Both give
// the serial answer.
TEST(Motion, ParallelCheckSharesOnlyAPathOfSlowChecks) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one hardware thread";
  const JointPath aroundTheWall{kStart, vec({-0.5, 0.7}), vec({0.5, 0.7}), kGoal};
  const auto threadsUsed = [&](std::chrono::microseconds perState, double resolution) {
    std::mutex mutex;
    std::set<std::thread::id> seen;
    const FunctionChecker checker("timed wall", 2, [&](const double* q) {
      const auto until = std::chrono::steady_clock::now() + perState;
      while (std::chrono::steady_clock::now() < until) {
      }
      const std::lock_guard lock(mutex);
      seen.insert(std::this_thread::get_id());
      return inWall(q);
    });
    EXPECT_TRUE(checkPathParallel(checker, aroundTheWall, resolution).valid());
    return seen.size();
  };
  EXPECT_EQ(threadsUsed(std::chrono::microseconds(50), 0.005), 2u);
  EXPECT_EQ(threadsUsed(std::chrono::microseconds(0), 0.05), 1u);
}

// A check that throws (here: a checker that fails on its 100th call) reaches the caller from
// whichever thread met it, and the other threads stop.
TEST(Motion, ParallelCheckRethrowsACheckersError) {
  std::atomic<int> calls{0};
  const FunctionChecker failing("failing", 2, [&](const double*) {
    if (++calls == 100) throw Error("the checker failed");
    return false;
  });
  const JointPath path{kStart, kGoal};
  EXPECT_THAT(messageOf<Error>([&] { checkPathParallel(failing, path, 0.001, 2); }),
              HasSubstr("the checker failed"));
}

TEST_F(Planning, EveryPlannerFindsAValidPathAndStopsAtItsFirstSolution) {
  const auto wall = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  for (const PlannerType type : allPlannerTypes()) {
    // A generous limit: a planner that kept optimising after its first solution would use it all.
    const PlannerOptions options{.type = type, .resolution = 0.01, .timeLimit = 30};
    const PlanResult plan = planMotion(wall, limits, kStart, kGoal, options);
    ASSERT_TRUE(plan.solved()) << plannerName(type) << ": " << toString(plan.status);
    EXPECT_LT(plan.time, std::chrono::seconds(5)) << plannerName(type) << " did not stop";
    EXPECT_TRUE(plan.path.front().isApprox(kStart));
    EXPECT_TRUE(plan.path.back().isApprox(kGoal));
    EXPECT_TRUE(pathIsFree(plan.path, 0.01, [](const Eigen::VectorXd& q) {
      return inWall(q.data());
    })) << plannerName(type);
    EXPECT_GT(pathLength(plan.path), 2.0) << "the path must go round the wall";
  }
}

// RRT-Connect's goal tree checks motions towards its nodes, and the simplifier motions ending at
// waypoints: the validator asks its source about such an end once, and answers alike after.
TEST_F(Planning, TheMotionValidatorAsksAboutAnEndStateOnce) {
  std::size_t asked = 0;
  const auto counting = std::make_shared<FunctionChecker>("counting wall", 2, [&](const double* q) {
    ++asked;
    return inWall(q);
  });
  const auto si = makeSpaceInformation(CollisionSource(counting), JointLimits::unitBox(2), 0.1);
  const auto& validator = dynamic_cast<const ResolutionMotionValidator&>(*si->getMotionValidator());
  ompl::base::ScopedState<> from(si), freeEnd(si), wallEnd(si);
  from[0] = -0.8, from[1] = -0.8;
  freeEnd[0] = -0.3, freeEnd[1] = -0.8;   // 5 states, all free
  wallEnd[0] = 0.05, wallEnd[1] = -0.75;  // ends inside the wall
  for (int round = 0; round < 2; ++round) {
    asked = 0;
    EXPECT_TRUE(validator.checkMotion(from.get(), freeEnd.get()));
    EXPECT_EQ(asked, round == 0 ? 5u : 4u) << "round " << round;
    asked = 0;
    EXPECT_FALSE(validator.checkMotion(from.get(), wallEnd.get()));
    EXPECT_EQ(asked, round == 0 ? 1u : 0u) << "the end is asked first, then remembered";
  }
  // The variant that reports the last valid state walks from s1 and agrees with a fresh walk.
  std::pair<ompl::base::State*, double> lastValid{nullptr, 0};
  EXPECT_FALSE(validator.checkMotion(from.get(), wallEnd.get(), lastValid));
  const auto fresh =
      makeSpaceInformation(CollisionSource(wallChecker()), JointLimits::unitBox(2), 0.1);
  std::pair<ompl::base::State*, double> freshValid{nullptr, 0};
  EXPECT_FALSE(fresh->getMotionValidator()->checkMotion(from.get(), wallEnd.get(), freshValid));
  EXPECT_EQ(lastValid.second, freshValid.second);
  asked = 0;
  EXPECT_TRUE(validator.checkMotion(from.get(), freeEnd.get(), lastValid));
  EXPECT_EQ(asked, 4u) << "the walk in order asks about the known free end no more";
}

// OMPL's PathSimplifier after every plan: the path stays valid under an independent check at a
// finer resolution and gets close to the shortest way over the wall (2 sqrt(0.7^2 + 1.3^2) =
// 2.95), which the raw RRT-Connect paths are not; the time it took is reported. So with shortcuts
// alone (what repairs' bridges get), whose paths are a little longer: over 1500 plans the median
// 1.11 times the shortest, 0.2% over 1.3 times, at most 1.43 (full: 1.10, at most 1.23), so their
// bound holds for the mean of the ten. A simplified path hugs the wall's corner, and a check every
// 0.02 cannot see a corner cut between two checked states; every point of the path is within 0.01
// of a checked free state, so the finer check is against the wall shrunk by that much: what
// discrete checking guarantees, and all it does.
TEST_F(Planning, SimplifiedPathsAreShortAndStayValid) {
  const auto wall = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  for (const PathSimplification simplification :
       {PathSimplification::Full, PathSimplification::Shortcuts}) {
    SCOPED_TRACE(simplificationName(simplification));
    const bool full = simplification == PathSimplification::Full;
    double rawLength = 0, simplifiedLength = 0;
    for (int query = 0; query < 10; ++query) {
      const PlannerOptions raw{.resolution = 0.02, .timeLimit = 5, .simplifyTime = 0};
      PlannerOptions simplified = raw;
      simplified.simplifyTime = 0.1;
      simplified.simplification = simplification;
      const PlanResult a = planMotion(wall, limits, kStart, kGoal, raw);
      const PlanResult b = planMotion(wall, limits, kStart, kGoal, simplified);
      ASSERT_TRUE(a.solved() && b.solved());
      EXPECT_EQ(a.simplifyTime.count(), 0);
      EXPECT_GT(b.simplifyTime.count(), 0);
      EXPECT_LE(b.simplifyTime, b.time);
      EXPECT_TRUE(b.path.front().isApprox(kStart) && b.path.back().isApprox(kGoal));
      EXPECT_TRUE(pathIsFree(b.path, 0.002,
                             [](const Eigen::VectorXd& q) {
                               return std::abs(q[0]) < 0.1 - 0.01 && q[1] < 0.5 - 0.01;
                             }))
          << "query " << query;
      EXPECT_LT(pathLength(b.path), 2.95 * (full ? 1.3 : 2.0)) << "query " << query;
      rawLength += pathLength(a.path);
      simplifiedLength += pathLength(b.path);
    }
    EXPECT_LT(simplifiedLength, 0.9 * rawLength);
    EXPECT_LT(simplifiedLength / 10, 2.95 * 1.3);
  }
  EXPECT_THAT(messageOf<InvalidArgument>([&] { validate(PlannerOptions{.simplifyTime = -1}); }),
              HasSubstr("path simplification time must be 0 (off) or positive, got -1"));
}

// OMPL's checkAndRepair, which ends both simplifications, cannot always move a state out of an
// obstacle, and then leaves an edge through it (about 1 in 1000 plans around the wall with
// shortcuts alone; with these seeds, query 261 did without the fix); the planner's own path,
// every edge of it checked, is returned instead.
TEST_F(Planning, ASimplificationThatEndsInvalidKeepsThePlannersPath) {
  const auto wall = wallChecker();
  for (const PathSimplification simplification :
       {PathSimplification::Shortcuts, PathSimplification::Full}) {
    SCOPED_TRACE(simplificationName(simplification));
    const int queries = simplification == PathSimplification::Shortcuts ? 400 : 200;
    for (int query = 0; query < queries; ++query) {
      seedPlanners(2, static_cast<std::uint64_t>(
                          query));  // the same plans in every run  // the same plans in every run
      const PlanResult plan = planMotion(wall, JointLimits::unitBox(2), kStart, kGoal,
                                         {.resolution = 0.02,
                                          .timeLimit = 5,
                                          .simplifyTime = 0.1,
                                          .simplification = simplification});
      ASSERT_TRUE(plan.solved());
      ASSERT_TRUE(checkPath(*wall, plan.path, 0.02).valid()) << "query " << query;
    }
  }
}

// Every exact answer of a verified plan is returned, and nothing else: one row per call the exact
// checker received, with its answer.
TEST_F(Planning, VerifiedPlansReturnEveryExactAnswer) {
  const auto exact = std::make_shared<FunctionChecker>("wall", 2, inWall);
  // A model-like source that misses the lower half of the wall: plans through it get repaired.
  const auto approximate = std::make_shared<FunctionChecker>("half wall", 2, [](const double* q) {
    return std::abs(q[0]) < 0.1 && q[1] > -0.2 && q[1] < 0.5;
  });
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{.resolution = 0.01, .timeLimit = 5};
  std::size_t repaired = 0;
  for (int query = 0; query < 5; ++query) {
    exact->resetCallCount();
    const VerifiedPlan plan = planVerified(approximate, exact, limits, kStart, kGoal, options);
    ASSERT_TRUE(plan.solved()) << plan.failure;
    repaired += plan.invalidStretches;
    EXPECT_EQ(plan.exactAnswers.size(), exact->callCount());
    EXPECT_EQ(plan.exactChecks, exact->callCount());
    ASSERT_FALSE(plan.attempts.empty());
    EXPECT_EQ(plan.attempts.front().source, "half wall");
    ASSERT_EQ(static_cast<std::size_t>(plan.exactAnswers.points.rows()), plan.exactAnswers.size());
    for (std::size_t i = 0; i < plan.exactAnswers.size(); ++i) {
      const double* q = plan.exactAnswers.points.row(static_cast<Eigen::Index>(i)).data();
      EXPECT_EQ(plan.exactAnswers.labels[i], inWall(q) ? 1 : -1);
    }
  }
  EXPECT_GT(repaired, 0u) << "the test needs plans through the missed half";
}

// After a repair, verification checks what the repair changed: the edges it kept were checked in
// the round before and are asked about no more. The repaired path is still free under an
// independent finer check.
TEST_F(Planning, VerificationAfterARepairChecksOnlyWhatChanged) {
  std::mutex mutex;
  std::multiset<std::pair<double, double>> askedOnKeptEdge;
  const auto exact = std::make_shared<FunctionChecker>("wall", 2, [&](const double* q) {
    if (q[1] == -0.95 && q[0] > -0.8 && q[0] < -0.3) {  // inside the edge every round keeps
      const std::lock_guard lock(mutex);
      askedOnKeptEdge.emplace(q[0], q[1]);
    }
    return inWall(q);
  });
  const JointLimits limits = JointLimits::unitBox(2);
  // The second edge crosses the wall; the first and the last stay clear of it.
  const JointPath path{vec({-0.8, -0.95}), vec({-0.3, -0.95}), vec({0.5, -0.5}), kGoal};
  const VerifiedPlan plan =
      verifyAndRepair(path, exact, limits, PlannerOptions{.resolution = 0.01, .timeLimit = 5});
  ASSERT_TRUE(plan.solved()) << plan.failure;
  EXPECT_EQ(plan.invalidStretches, 1u);
  EXPECT_TRUE(plan.path.front().isApprox(path[0]) && plan.path[1].isApprox(path[1]));
  EXPECT_TRUE(pathIsFree(plan.path, 0.005, [](const Eigen::VectorXd& q) {
    return std::abs(q[0]) < 0.1 - 0.01 && q[1] < 0.5 - 0.01;
  }));
  ASSERT_GT(askedOnKeptEdge.size(), 40u);  // the first round checked it every 0.01
  for (const auto& q : askedOnKeptEdge) {
    EXPECT_EQ(askedOnKeptEdge.count(q), 1u)
        << "asked again about (" << q.first << ", " << q.second << ")";
  }
}

// A model that learned a wall without its lower half plans through it; with learning from
// verification it learns the exact answers it got wrong and plans again before anything is
// repaired, and keeps what it learned.
TEST_F(Planning, AModelLearnsFromVerificationAndPlansAgain) {
  const auto exact = std::make_shared<FunctionChecker>("wall", 2, inWall);
  const auto halfWall = std::make_shared<FunctionChecker>("half wall", 2, [](const double* q) {
    return std::abs(q[0]) < 0.1 && q[1] > -0.2 && q[1] < 0.5;
  });
  const JointLimits limits = JointLimits::unitBox(2);
  ProxyCollisionDetector proxy(halfWall, limits, learningProxyParams());
  proxy.initialize(1500);
  const auto first = proxy.calibratedModel();
  ASSERT_FALSE(first.model->inCollision(vec({0, -0.8}).data())) << "the model must miss the half";

  const PlannerOptions options{.resolution = 0.01, .timeLimit = 5, .verify = {.learningRounds = 3}};
  exact->resetCallCount();
  const VerifiedPlan plan = planVerifiedLearning(proxy, exact, limits, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  EXPECT_TRUE(
      pathIsFree(plan.path, 0.01, [](const Eigen::VectorXd& x) { return inWall(x.data()); }));
  EXPECT_GE(plan.relearned, 1u) << "the first model's path crosses the missed half";
  EXPECT_LE(plan.relearned, options.verify.learningRounds);
  EXPECT_EQ(proxy.calibratedModel().version, first.version + plan.relearned);
  EXPECT_GT(plan.learnTime.count(), 0);
  EXPECT_LE(plan.learnTime, plan.planTime);
  // Every exact answer of every round, and nothing else.
  EXPECT_EQ(plan.exactAnswers.size(), exact->callCount());
  for (std::size_t i = 0; i < plan.exactAnswers.size(); ++i) {
    const double* q = plan.exactAnswers.points.row(static_cast<Eigen::Index>(i)).data();
    ASSERT_EQ(plan.exactAnswers.labels[i], inWall(q) ? 1 : -1);
  }
  // The proxy keeps what it learned: where the paths crossed the missed half, the model now
  // says "collides" (the first one said "free" everywhere there).
  const auto collidingInMissedHalf = [](const Model& model) {
    int count = 0;
    for (double y = -0.99; y < -0.2; y += 0.02) {
      for (const double x : {-0.05, 0.0, 0.05}) count += model.inCollision(vec({x, y}).data());
    }
    return count;
  };
  EXPECT_EQ(collidingInMissedHalf(*first.model), 0);
  EXPECT_GT(collidingInMissedHalf(*proxy.model()), 0);

  // No learning rounds: the model's first path is repaired, as planVerified does, and the proxy
  // learns nothing.
  ProxyCollisionDetector unlearned(halfWall, limits, learningProxyParams());
  unlearned.initialize(1500);
  const VerifiedPlan repaired = planVerifiedLearning(
      unlearned, exact, limits, kStart, kGoal,
      PlannerOptions{.resolution = 0.01, .timeLimit = 5, .verify = {.learningRounds = 0}});
  ASSERT_TRUE(repaired.solved()) << repaired.failure;
  EXPECT_EQ(repaired.relearned, 0u);
  EXPECT_GT(repaired.invalidStretches, 0u);
  EXPECT_EQ(unlearned.calibratedModel().version, 1u);
}

// A source that closes the only passage finds no path however long it searches: the exact
// fallback starts after approximateShare of the time limit, not after all of it.
TEST_F(Planning, HopelessApproximatePlansAreTimeBoxed) {
  const auto exact = wallChecker();
  const auto closed = std::make_shared<FunctionChecker>(
      "closed", 2, [](const double* q) { return std::abs(q[0]) < 0.1; });
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{
      .resolution = 0.01, .timeLimit = 4, .verify = {.approximateShare = 0.05}};
  const VerifiedPlan plan = planVerified(closed, exact, limits, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  EXPECT_TRUE(plan.wholePathReplanned);
  EXPECT_LT(plan.planTime, std::chrono::milliseconds(1000)) << "0.2 s of a 4 s limit";
  EXPECT_GE(plan.planTime, std::chrono::milliseconds(150));
  EXPECT_THROW(validate(PlannerOptions{.verify = {.approximateShare = 0}}), InvalidArgument);
  EXPECT_THROW(validate(PlannerOptions{.verify = {.approximateShare = 1.5}}), InvalidArgument);
  EXPECT_THROW(validate(PlannerOptions{.verify = {.stretchShare = 0}}), InvalidArgument);
  EXPECT_THROW(validate(PlannerOptions{.verify = {.stretchShare = 1.5}}), InvalidArgument);
}

// A model that closes the gap: planning falls back from it to the hybrid source, which asks the
// exact checker inside the calibrated band, before planning the whole motion on the exact checker.
TEST_F(Planning, AModelThatClosesThePassageFallsBackToItsHybridBeforeTheExactChecker) {
  const auto exact = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  const auto closedWall = [](const double* q) { return std::abs(q[0]) < 0.1; };
  const Configurations q = test::uniformPoints(3000, 2, 11);
  Labels y(static_cast<std::size_t>(q.rows()));
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    y[static_cast<std::size_t>(i)] = closedWall(q.row(i).data()) ? 1 : -1;
  Trainer trainer(limits, {.kernel = {.gamma = 30}, .beta = 10});
  trainer.addPoints(q, y);
  trainer.update();
  CalibratedModel model{trainer.model(), {}};
  ASSERT_TRUE(model.model->inCollision(vec({0, 0.8}).data())) << "the model must close the gap";
  // Held-out labels of the true world; no false alarm allowed, so the band covers the gap.
  const Configurations heldOut = test::uniformPoints(4000, 2, 12);
  Labels truth(static_cast<std::size_t>(heldOut.rows()));
  for (Eigen::Index i = 0; i < heldOut.rows(); ++i)
    truth[static_cast<std::size_t>(i)] = inWall(heldOut.row(i).data()) ? 1 : -1;
  model.calibration = calibrateBand(model.model->scoreBatch(heldOut), truth, {.falseAlarmRate = 0});
  const PlannerOptions options{
      .resolution = 0.01, .timeLimit = 4, .verify = {.approximateShare = 0.05}};
  const VerifiedPlan plan = planVerified(model, exact, limits, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  EXPECT_EQ(plan.plannedOn, "Fastron+wall");
  EXPECT_FALSE(plan.wholePathReplanned);
  EXPECT_LT(plan.planTime, std::chrono::milliseconds(1500)) << "two shares of 0.2 s at most";
  EXPECT_TRUE(
      pathIsFree(plan.path, 0.01, [](const Eigen::VectorXd& x) { return inWall(x.data()); }));
  // The hybrid's exact answers are recorded with verification's.
  std::size_t inGap = 0;
  for (std::size_t i = 0; i < plan.exactAnswers.size(); ++i) {
    const double* x = plan.exactAnswers.points.row(static_cast<Eigen::Index>(i)).data();
    EXPECT_EQ(plan.exactAnswers.labels[i], inWall(x) ? 1 : -1);
    inGap += std::abs(x[0]) < 0.1 && x[1] >= 0.5 ? 1 : 0;
  }
  EXPECT_GT(inGap, 0u) << "the hybrid asked the exact checker in the gap";
  // Without a calibrated band there is no hybrid step: the model's failure goes to the exact
  // checker directly.
  const VerifiedPlan uncalibrated =
      planVerified(CalibratedModel{model.model, {}}, exact, limits, kStart, kGoal, options);
  ASSERT_TRUE(uncalibrated.solved()) << uncalibrated.failure;
  EXPECT_EQ(uncalibrated.plannedOn, "wall");
  EXPECT_TRUE(uncalibrated.wholePathReplanned);
  EXPECT_THROW(planVerified(CalibratedModel{}, exact, limits, kStart, kGoal, options),
               InvalidArgument);
}

// A model that learns and closes the gap: its first plan is time-boxed to modelShare, then a
// hybrid that trusts only the model's "free" asks the exact checker about every "collides" and
// finds the gap, before the exact checker would plan the whole motion.
TEST_F(Planning, ALearningModelThatClosesThePassageFallsBackToAHybridAskingAboutEveryCollision) {
  const auto exact = std::make_shared<FunctionChecker>("wall", 2, inWall);
  const auto closed = std::make_shared<FunctionChecker>(
      "closed", 2, [](const double* q) { return std::abs(q[0]) < 0.1; });
  const JointLimits limits = JointLimits::unitBox(2);
  ProxyCollisionDetector proxy(closed, limits,
                               learningProxyParams());  // learns a world without the gap
  proxy.initialize(1500);
  const std::shared_ptr<const Model> model = proxy.model();
  ASSERT_TRUE(model->inCollision(vec({0, 0.8}).data())) << "the model must close the gap";

  const PlannerOptions options{.resolution = 0.01,
                               .timeLimit = 4,
                               .verify = {.approximateShare = 0.25, .modelShare = 0.025}};
  exact->resetCallCount();
  const VerifiedPlan plan = planVerifiedLearning(proxy, exact, limits, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  EXPECT_EQ(plan.plannedOn, "Fastron+wall");
  EXPECT_FALSE(plan.wholePathReplanned);
  EXPECT_EQ(plan.relearned, 0u) << "the model found no path to learn from";
  EXPECT_GE(plan.planTime, std::chrono::milliseconds(90)) << "the model's 0.1 s, all of it";
  EXPECT_LT(plan.planTime, std::chrono::milliseconds(1500)) << "0.1 s and 1 s at most";
  EXPECT_TRUE(
      pathIsFree(plan.path, 0.01, [](const Eigen::VectorXd& x) { return inWall(x.data()); }));
  // Every exact answer is recorded, and the hybrid asked in the gap, where the model says
  // "collides".
  EXPECT_EQ(plan.exactAnswers.size(), exact->callCount());
  std::size_t inGap = 0;
  for (std::size_t i = 0; i < plan.exactAnswers.size(); ++i) {
    const double* x = plan.exactAnswers.points.row(static_cast<Eigen::Index>(i)).data();
    EXPECT_EQ(plan.exactAnswers.labels[i], inWall(x) ? 1 : -1);
    inGap += std::abs(x[0]) < 0.1 && x[1] >= 0.5 && model->inCollision(x) ? 1 : 0;
  }
  EXPECT_GT(inGap, 0u) << "the hybrid asked the exact checker in the gap";
  EXPECT_THROW(validate(PlannerOptions{.verify = {.modelShare = 0}}), InvalidArgument);
  EXPECT_THROW(validate(PlannerOptions{.verify = {.modelShare = 1.5}}), InvalidArgument);
}

// With oracleRelaxesExact planVerifiedLearning asked the proxy's oracle (without it, never), and
// exactAnswers holds the exact checker's answers only.
void expectOracleAskedOnlyWhenRelaxed(const VerifiedPlan& plan, const FunctionChecker& oracle,
                                      const FunctionChecker& exact, bool relaxed) {
  if (relaxed) {
    EXPECT_GT(oracle.callCount(), 0u);
  } else {
    EXPECT_EQ(oracle.callCount(), 0u);
  }
  EXPECT_EQ(plan.exactAnswers.size(), exact.callCount());
  // The plan's own counts: every call either checker got for it.
  EXPECT_EQ(plan.exactChecks, exact.callCount());
  EXPECT_EQ(plan.relaxedChecks, oracle.callCount());
}

// With oracleRelaxesExact the hybrid asks the proxy's oracle, not the exact checker: here an oracle
// that taught the model a world without the gap, then answers as the exact checker does (a
// relaxation of it, as FCL without self-collision is of FCL with it).
TEST_F(Planning, ALearningModelsHybridAsksItsOracleWhenTold) {
  const auto exact = std::make_shared<FunctionChecker>("wall", 2, inWall);
  std::atomic<bool> gapOpen{false};
  const auto oracle = std::make_shared<FunctionChecker>(
      "oracle", 2, [&](const double* q) { return gapOpen ? inWall(q) : std::abs(q[0]) < 0.1; });
  const JointLimits limits = JointLimits::unitBox(2);
  PlannerOptions options{.resolution = 0.01,
                         .timeLimit = 4,
                         .verify = {.approximateShare = 0.25, .modelShare = 0.025}};
  for (const bool asksOracle : {false, true}) {
    gapOpen = false;
    ProxyCollisionDetector proxy(oracle, limits, learningProxyParams());
    proxy.initialize(1500);
    ASSERT_TRUE(proxy.model()->inCollision(vec({0, 0.8}).data())) << "the model closes the gap";
    gapOpen = true;
    options.verify.oracleRelaxesExact = asksOracle;
    oracle->resetCallCount();
    exact->resetCallCount();
    const VerifiedPlan plan = planVerifiedLearning(proxy, exact, limits, kStart, kGoal, options);
    ASSERT_TRUE(plan.solved()) << plan.failure;
    EXPECT_EQ(plan.plannedOn, asksOracle ? "Fastron+oracle" : "Fastron+wall");
    // Where the time went: the model closed the gap, then its hybrid found the path.
    ASSERT_EQ(plan.attempts.size(), 2u);
    EXPECT_EQ(plan.attempts[0].source, "Fastron");
    EXPECT_NE(plan.attempts[0].status, PlanStatus::Solved);
    EXPECT_EQ(plan.attempts[1].source, plan.plannedOn);
    EXPECT_EQ(plan.attempts[1].status, PlanStatus::Solved);
    EXPECT_EQ(plan.attempts[0].time + plan.attempts[1].time, plan.planTime - plan.learnTime);
    EXPECT_TRUE(
        pathIsFree(plan.path, 0.01, [](const Eigen::VectorXd& x) { return inWall(x.data()); }));
    expectOracleAskedOnlyWhenRelaxed(plan, *oracle, *exact, asksOracle);
  }
}

// With oracleRelaxesExact the first repair round bridges on the proxy's oracle. Here the oracle
// lacks a bar of the exact checker's in the wall's gap (as FCL without self-collision lacks the
// robot's own links): a bridge through the bar fails the next verification and is bridged again on
// the exact checker, so the final path is free either way.
TEST_F(Planning, ALearningModelsFirstRepairsBridgeOnItsOracleWhenTold) {
  const auto inBar = [](const double* q) { return std::abs(q[0]) < 0.1 && q[1] < 0.8; };
  const auto exact = std::make_shared<FunctionChecker>("wall and bar", 2, inBar);
  std::atomic<bool> wallBuilt{false};
  const auto oracle = std::make_shared<FunctionChecker>("oracle", 2, [&](const double* q) {
    // Before the wall: a corner post, so that the model knows some collisions but none between
    // start and goal, and plans through the wall.
    return wallBuilt ? inWall(q) : q[0] > 0.7 && q[1] > 0.7;
  });
  const JointLimits limits = JointLimits::unitBox(2);
  PlannerOptions options{.resolution = 0.01,
                         .timeLimit = 4,
                         .verify = {.approximateShare = 0.25, .modelShare = 0.025}};
  for (const bool relaxes : {false, true}) {
    SCOPED_TRACE(relaxes ? "bridges on the oracle first" : "bridges on the exact checker");
    wallBuilt = false;
    ProxyCollisionDetector proxy(oracle, limits, learningProxyParams());
    proxy.initialize(1500);
    ASSERT_FALSE(proxy.model()->inCollision(vec({0, -0.8}).data())) << "the model misses the wall";
    wallBuilt = true;
    options.verify.oracleRelaxesExact = relaxes;
    oracle->resetCallCount();
    exact->resetCallCount();
    const VerifiedPlan plan = planVerifiedLearning(proxy, exact, limits, kStart, kGoal, options);
    ASSERT_TRUE(plan.solved()) << plan.failure;
    EXPECT_GE(plan.invalidStretches, 1u) << "the model's path was repaired";
    EXPECT_TRUE(pathIsFree(plan.path, 0.01, [&](const Eigen::VectorXd& x) {
      return inBar(x.data());
    })) << "the final path is free under the exact checker";
    expectOracleAskedOnlyWhenRelaxed(plan, *oracle, *exact, relaxes);
  }
}

// A stretch whose first collision the relaxed oracle finds free (as FCL without self-collision
// misses the robot's own links) is bridged on the exact checker at once: on the oracle its bridge
// would cross the same wall and need a second round. Here the oracle knows only a corner post, so
// the model's path runs straight into the exact checker's wall, which the oracle lacks.
TEST_F(Planning, AStretchTheOracleCannotSeeIsBridgedOnTheExactChecker) {
  const auto inPost = [](const double* q) { return q[0] > 0.7 && q[1] > 0.7; };
  const auto inWallOrPost = [&](const double* q) { return inWall(q) || inPost(q); };
  const auto exact = std::make_shared<FunctionChecker>("wall and post", 2, inWallOrPost);
  const auto oracle = std::make_shared<FunctionChecker>("post", 2, inPost);
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{
      .resolution = 0.01,
      .timeLimit = 4,
      .verify = {.approximateShare = 0.25, .modelShare = 0.025, .oracleRelaxesExact = true}};
  std::size_t repaired = 0;
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    seedPlanners(seed, 0);
    ProxyCollisionDetector proxy(oracle, limits, learningProxyParams());
    proxy.initialize(1500);
    const VerifiedPlan plan = planVerifiedLearning(proxy, exact, limits, kStart, kGoal, options);
    ASSERT_TRUE(plan.solved()) << plan.failure;
    EXPECT_TRUE(pathIsFree(plan.path, 0.01, [&](const Eigen::VectorXd& x) {
      return inWallOrPost(x.data());
    })) << "the final path is free under the exact checker";
    EXPECT_LE(plan.invalidStretches, 1u) << "one stretch through the wall, bridged once";
    EXPECT_FALSE(plan.wholePathReplanned);
    repaired += plan.invalidStretches;
  }
  EXPECT_GE(repaired, 3u) << "the model's paths must meet the wall";
}

// The optimistic hybrid's range is half the planner's: half of OMPL's own default (which OMPL
// computes from the space) when no range is set.
TEST_F(Planning, TheOptimisticHybridPlansWithHalfThePlannersRange) {
  // The Panda's joint limits: OMPL's default range there is 2.6 rad.
  const JointLimits panda(vec({-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973}),
                          vec({2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973}));
  const auto si = makeSpaceInformation(
      CollisionSource(std::shared_ptr<const CollisionChecker>(
          std::make_shared<FunctionChecker>("free", 7, [](const double*) { return false; }))),
      panda, 0.05);
  ompl::geometric::RRTConnect ompl(si);
  ompl.setup();
  ASSERT_GT(ompl.getRange(), 2.5);
  EXPECT_NEAR(optimisticHybridRange(PlannerOptions{}, panda), 0.5 * ompl.getRange(), 1e-12);
  EXPECT_DOUBLE_EQ(optimisticHybridRange(PlannerOptions{.range = 2}, panda), 1);
  EXPECT_DOUBLE_EQ(
      optimisticHybridRange(PlannerOptions{.range = 2, .verify = {.hybridRange = 0.7}}, panda),
      0.7);
  EXPECT_THROW(validate(PlannerOptions{.verify = {.hybridRange = -1}}), InvalidArgument);
  EXPECT_THROW(validate(PlannerOptions{.verify = {.hybridRange = std::nan("")}}), InvalidArgument);

  // planVerifiedLearning's hybrid plans at that range: this model closes the gap of a thinner
  // wall (so that what it calls free is free, and nothing is repaired), so the hybrid plans, and
  // unsimplified, each edge of its path is one RRT-Connect motion, at most the range long (the
  // planner's own range here is 0.57).
  const auto exact = std::make_shared<FunctionChecker>(
      "wall", 2, [](const double* q) { return std::abs(q[0]) < 0.05 && q[1] < 0.5; });
  const auto closed = std::make_shared<FunctionChecker>(
      "closed", 2, [](const double* q) { return std::abs(q[0]) < 0.1; });
  const JointLimits square = JointLimits::unitBox(2);
  ProxyCollisionDetector proxy(closed, square, learningProxyParams());
  proxy.initialize(1500);
  const PlannerOptions options{
      .resolution = 0.01,
      .modelResolution = 0.01,  // the states verification checks
      .timeLimit = 4,
      .simplifyTime = 0,
      .verify = {.approximateShare = 0.25, .modelShare = 0.025, .hybridRange = 0.1}};
  const VerifiedPlan plan = planVerifiedLearning(proxy, exact, square, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  ASSERT_EQ(plan.plannedOn, "Fastron+wall");
  ASSERT_EQ(plan.invalidStretches, 0u) << "a repair's motions have the planner's range";
  double longest = 0;
  for (std::size_t i = 1; i < plan.path.size(); ++i) {
    longest = std::max(longest, (plan.path[i] - plan.path[i - 1]).norm());
  }
  EXPECT_LE(longest, 0.1 + 1e-9);
}

// The range schedule: OMPL's default while RRT-Connect finds its path in the first rangeStage
// iterations (an open square); without a path (a wall across the whole square between start
// and goal, each tree free to fill its half, so neither is in a pocket: see
// ATreeInAPocketGrowsAtHalfTheShortestRange) halved after every rangeStage iterations down to the
// first range over 2^rangeHalvings, then the first again, each round of ranges twice as long.
// rangeStage 0 keeps the range.
TEST_F(Planning, TheRangeIsHalvedAfterEachStageWithoutAPathAndGoesRound) {
  const JointLimits square = JointLimits::unitBox(2);
  const double ompls = 0.2 * std::sqrt(8.0);  // a fifth of the square's diagonal
  const auto open =
      std::make_shared<FunctionChecker>("open", 2, [](const double*) { return false; });
  const PlannerOptions automatic{.resolution = 0.01, .timeLimit = 2, .simplifyTime = 0};
  const PlanResult easy = planMotion(open, square, kStart, kGoal, automatic);
  ASSERT_TRUE(easy.solved());
  EXPECT_NEAR(easy.range, ompls, 1e-12);

  const auto across = std::make_shared<FunctionChecker>(
      "across", 2, [](const double* q) { return std::abs(q[0]) < 0.05; });
  const auto si = makeSpaceInformation(CollisionSource(across), square, 0.01);
  // The range after `total` iterations, counted by the planner's own stop condition.
  const auto rangeAfter = [&](const PlannerOptions& options, std::size_t total) {
    const auto planner = makePlanner(si, options);
    planner->setProblemDefinition(makeProblemDefinition(si, kStart, kGoal, options.type));
    planner->setup();
    RangeSchedule schedule(*planner, options);
    std::size_t iterations = 0;
    const auto status = schedule.solve(
        *planner, ompl::base::PlannerTerminationCondition([&] { return ++iterations > total; }));
    EXPECT_NE(status, ompl::base::PlannerStatus::EXACT_SOLUTION);
    return planner->as<ompl::geometric::RRTConnect>()->getRange();
  };
  // A first round of 100 iterations per range, a second of 200 (from 400), a third of 400
  // (from 1200).
  EXPECT_NEAR(rangeAfter(automatic, 50), ompls, 1e-12);
  EXPECT_NEAR(rangeAfter(automatic, 150), ompls / 2, 1e-12);
  EXPECT_NEAR(rangeAfter(automatic, 250), ompls / 4, 1e-12);
  EXPECT_NEAR(rangeAfter(automatic, 350), ompls / 8, 1e-12);
  EXPECT_NEAR(rangeAfter(automatic, 450), ompls, 1e-12);
  EXPECT_NEAR(rangeAfter(automatic, 650), ompls / 2, 1e-12);
  EXPECT_NEAR(rangeAfter(automatic, 850), ompls / 4, 1e-12);
  EXPECT_NEAR(rangeAfter(automatic, 1100), ompls / 8, 1e-12);
  EXPECT_NEAR(rangeAfter(automatic, 1300), ompls, 1e-12);

  PlannerOptions twice = automatic;
  twice.rangeHalvings = 2;
  EXPECT_NEAR(rangeAfter(twice, 250), ompls / 4, 1e-12);
  EXPECT_NEAR(rangeAfter(twice, 350), ompls, 1e-12);
  PlannerOptions given = automatic;
  given.range = 0.3;
  EXPECT_DOUBLE_EQ(rangeAfter(given, 150), 0.15);
  PlannerOptions stays = given;
  stays.rangeStage = 0;
  EXPECT_DOUBLE_EQ(rangeAfter(stays, 1450), 0.3);
  EXPECT_DOUBLE_EQ(planMotion(across, square, kStart, kGoal, stays).range, 0.3);

  EXPECT_EQ(describeRange(stays, "rad"), "0.3 rad");
  EXPECT_EQ(describeRange(automatic, "rad"),
            "OMPL's default, halved after 100 iterations without a path down to 1/8 of it, then "
            "again from it, each round twice as long as the one before; a tree in a pocket "
            "grows at 1/16 of it");
  PlannerOptions tooMany = automatic;
  tooMany.rangeHalvings = kMaxRangeHalvings + 1;
  EXPECT_THAT(messageOf<InvalidArgument>([&] { validate(tooMany); }), HasSubstr("rangeHalvings"));
}

// A tree in a pocket: in the unit box of four joints (OMPL's range there 0.8, the schedule's
// shortest 0.1), the goal in a free ball of radius 0.08 walled in by a shell out to 0.4. Every
// extension from the goal at a range of the schedule crosses the shell, so its tree gains
// nothing in the first round (400 iterations) while the start tree fills the box: the schedule
// finds the goal tree in a pocket, and from then on the goal tree grows at half the shortest
// range (0.05, inside the ball) while the start tree keeps the schedule. Across a wall that
// parts the box (no path either, but each tree free to fill its side) no tree is in a pocket.
TEST_F(Planning, ATreeInAPocketGrowsAtHalfTheShortestRange) {
  const JointLimits box = JointLimits::unitBox(4);
  const double ompls = 0.2 * std::sqrt(16.0);
  const Eigen::VectorXd start = vec({-0.6, 0.6, -0.6, 0.6});
  const Eigen::VectorXd goal = vec({0.6, -0.6, 0.6, -0.6});
  const auto pocket = std::make_shared<FunctionChecker>("pocket", 4, [&goal](const double* q) {
    const double r = (Eigen::Map<const Eigen::Vector4d>(q) - goal).norm();
    return r > 0.08 && r < 0.4;
  });
  const auto across = std::make_shared<FunctionChecker>(
      "across", 4, [](const double* q) { return std::abs(q[0]) < 0.05; });
  const PlannerOptions options{.resolution = 0.01, .timeLimit = 2, .simplifyTime = 0};
  // The schedule and its trees after `total` iterations (none finds a path: neither world has
  // one).
  struct Run {
    PocketTree pocket;
    std::size_t startNodes, goalNodes;
  };
  const auto runFor = [&](const std::shared_ptr<const CollisionChecker>& checker,
                          std::size_t total) {
    seedPlanners(3, 0);
    const auto si = makeSpaceInformation(CollisionSource(checker), box, options.resolution);
    const auto planner = makePlanner(si, options);
    planner->setProblemDefinition(makeProblemDefinition(si, start, goal, options.type));
    planner->setup();
    EXPECT_DOUBLE_EQ(planner->as<RrtConnectTrees>()->getRange(), ompls);
    RangeSchedule schedule(*planner, options);
    std::size_t iterations = 0;
    schedule.solve(*planner,
                   ompl::base::PlannerTerminationCondition([&] { return ++iterations > total; }));
    const auto* trees = planner->as<RrtConnectTrees>();
    return Run{schedule.pocket(), trees->startTreeSize(), trees->goalTreeSize()};
  };
  const Run firstRound = runFor(pocket, 390);
  EXPECT_EQ(firstRound.pocket, PocketTree::None) << "judged at a round's end only";
  EXPECT_EQ(firstRound.goalNodes, 1u);
  EXPECT_GT(firstRound.startNodes, RangeSchedule::kPocketSizeRatio);

  const Run later = runFor(pocket, 2000);
  EXPECT_EQ(later.pocket, PocketTree::Goal);
  // At the schedule's ranges, a node in the ball needs a sample inside it: 1 in 80000.
  EXPECT_GE(later.goalNodes, 4u) << "the goal tree grows inside its ball";

  const Run parted = runFor(across, 2000);
  EXPECT_EQ(parted.pocket, PocketTree::None);
  EXPECT_GT(parted.goalNodes * RangeSchedule::kPocketSizeRatio, parted.startNodes)
      << "both trees grow";
}

// A model whose goal sits in a pocket it closed all round (a ring of "collides" 0.2 from the
// goal; free at the goal, colliding from 0.03 out): RRT-Connect's goal tree can never grow, so a
// plan on the model stops after enclosedAfter iterations instead of searching until its time
// limit. An exact checker with the same pocket is searched until the limit, as is the model with
// the rule off.
TEST_F(Planning, APlanOnAModelStopsWhenAnEndIsEnclosed) {
  const JointLimits limits = JointLimits::unitBox(2);
  const Eigen::VectorXd goal = vec({0.6, 0.6});
  std::vector<Eigen::VectorXd> points;
  std::vector<double> weights;
  for (int k = 0; k < 48; ++k) {  // the ring
    const double angle = 2 * std::numbers::pi * k / 48;
    points.push_back(goal + 0.2 * vec({std::cos(angle), std::sin(angle)}));
    weights.push_back(1);
  }
  points.push_back(goal);  // the pocket
  weights.push_back(-2.3);
  for (double x = -1; x <= 1.001; x += 0.2) {  // free space elsewhere
    for (double y = -1; y <= 1.001; y += 0.2) {
      if ((vec({x, y}) - goal).norm() < 0.35) continue;
      points.push_back(vec({x, y}));
      weights.push_back(-1);
    }
  }
  Configurations support(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    support.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  }
  const auto model = std::make_shared<const Model>(
      FeatureMap::jointScaling(limits), Kernel{KernelType::RationalQuadratic, 200}, support,
      Eigen::Map<const Eigen::VectorXd>(weights.data(), static_cast<Eigen::Index>(weights.size())));
  ASSERT_FALSE(model->inCollision(goal.data()));
  ASSERT_FALSE(model->inCollision(kStart.data()));
  for (int k = 0; k < 16; ++k) {
    const double angle = 2 * std::numbers::pi * k / 16;
    for (const double r : {0.03, 0.1, 0.2, 0.3}) {
      const Eigen::VectorXd q = goal + r * vec({std::cos(angle), std::sin(angle)});
      ASSERT_TRUE(model->inCollision(q.data())) << "r " << r << ", angle " << angle;
    }
  }

  PlannerOptions options{.resolution = 0.01, .timeLimit = 1};
  seedPlanners(3, 0);
  const PlanResult stopped = planMotion(model, limits, kStart, goal, options);
  EXPECT_EQ(stopped.status, PlanStatus::Timeout);
  EXPECT_LT(stopped.time, std::chrono::milliseconds(300)) << "256 iterations, not 1 s";

  options.enclosedAfter = 0;
  seedPlanners(3, 0);
  const PlanResult searched = planMotion(model, limits, kStart, goal, options);
  EXPECT_EQ(searched.status, PlanStatus::Timeout);
  EXPECT_GE(searched.time, std::chrono::milliseconds(950));

  options.enclosedAfter = 256;
  const auto enclosing = std::make_shared<FunctionChecker>(
      "enclosing", 2, [&](const double* q) { return model->inCollision(q); });
  const PlanResult exact = planMotion(enclosing, limits, kStart, goal, options);
  EXPECT_EQ(exact.status, PlanStatus::Timeout);
  EXPECT_GE(exact.time, std::chrono::milliseconds(950)) << "an exact checker is never given up";
}

// A learning model that finds both ends colliding, with no state it finds free within reach of
// the start to plan from: the hybrid, which asks the exact checker about the ends, plans from them.
TEST_F(Planning, ALearningModelThatFindsTheEndsCollidingLeavesThemToItsHybrid) {
  const auto exact = std::make_shared<FunctionChecker>("wall", 2, inWall);
  const auto aroundEnds =
      std::make_shared<FunctionChecker>("around the ends", 2, [](const double* q) {
        return std::hypot(q[0] - kStart[0], q[1] - kStart[1]) < 1.9 || std::abs(q[0]) < 0.1;
      });
  const JointLimits limits = JointLimits::unitBox(2);
  ProxyCollisionDetector proxy(aroundEnds, limits, learningProxyParams());
  proxy.initialize(1500);
  ASSERT_TRUE(proxy.model()->inCollision(kStart.data()));
  ASSERT_TRUE(proxy.model()->inCollision(kGoal.data()));
  const PlannerOptions options{.resolution = 0.01,
                               .timeLimit = 4,
                               .verify = {.approximateShare = 0.25, .modelShare = 0.025}};
  const VerifiedPlan plan = planVerifiedLearning(proxy, exact, limits, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  EXPECT_EQ(plan.plannedOn, "Fastron+wall");
  EXPECT_FALSE(plan.wholePathReplanned);
  EXPECT_TRUE(
      pathIsFree(plan.path, 0.01, [](const Eigen::VectorXd& x) { return inWall(x.data()); }));
}

// An approximate checker that calls the goal colliding, and closes the gap: its plan between
// substitute ends gets substituteShare of the limit, not approximateShare, before the exact
// checker plans the whole motion.
TEST_F(Planning, APlanBetweenSubstituteEndsGetsItsOwnShare) {
  const auto exact = wallChecker();
  const auto closedAroundGoal =
      std::make_shared<FunctionChecker>("closed, goal in a disc", 2, [](const double* q) {
        return std::abs(q[0]) < 0.1 || std::hypot(q[0] - kGoal[0], q[1] - kGoal[1]) < 0.1;
      });
  const JointLimits limits = JointLimits::unitBox(2);
  const auto planTime = [&](double substituteShare) {
    const PlannerOptions options{
        .resolution = 0.01,
        .timeLimit = 4,
        .verify = {.approximateShare = 0.1, .substituteShare = substituteShare}};
    const VerifiedPlan plan =
        planVerified(CollisionSource(std::shared_ptr<const CollisionChecker>(closedAroundGoal)),
                     exact, limits, kStart, kGoal, options);
    EXPECT_TRUE(plan.solved()) << plan.failure;
    EXPECT_TRUE(plan.substituteEnds);
    EXPECT_TRUE(plan.wholePathReplanned)
        << "the closed wall leaves the motion to the exact checker";
    EXPECT_TRUE(
        pathIsFree(plan.path, 0.01, [](const Eigen::VectorXd& x) { return inWall(x.data()); }));
    return plan.planTime;
  };
  EXPECT_LT(planTime(0.01), std::chrono::milliseconds(300))
      << "40 ms, not approximateShare's 0.4 s";
  EXPECT_GE(planTime(1), std::chrono::milliseconds(350)) << "capped by approximateShare's 0.4 s";
  EXPECT_THROW(validate(PlannerOptions{.verify = {.substituteShare = 0}}), InvalidArgument);
  EXPECT_THROW(validate(PlannerOptions{.verify = {.substituteShare = 2}}), InvalidArgument);
}

// Seeded planners repeat their plans; another query's seed gives another plan.
TEST_F(Planning, SeededPlannersRepeatTheirPlans) {
  const auto exact = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  const auto planOf = [&](std::uint64_t query, PlannerType type) {
    seedPlanners(7, query);
    const PlanResult plan = planMotion(exact, limits, kStart, kGoal,
                                       {.type = type, .resolution = 0.01, .timeLimit = 5});
    EXPECT_TRUE(plan.solved());
    return plan.path;
  };
  for (const PlannerType type : {PlannerType::RrtConnect, PlannerType::Rrt}) {
    const JointPath first = planOf(3, type);
    const JointPath again = planOf(3, type);
    ASSERT_EQ(first.size(), again.size()) << plannerName(type);
    for (std::size_t i = 0; i < first.size(); ++i) {
      EXPECT_EQ(first[i], again[i]) << plannerName(type) << ", waypoint " << i;
    }
    EXPECT_NE(pathLength(first), pathLength(planOf(4, type))) << plannerName(type);
  }
  // Re-seeding after OMPL's first generators, which OMPL reports as an error, logs nothing.
  struct Recorder final : ompl::msg::OutputHandler {
    std::vector<std::string> lines;
    void log(const std::string& text, ompl::msg::LogLevel, const char*, int) override {
      lines.push_back(text);
    }
  } recorder;
  ompl::msg::useOutputHandler(&recorder);
  const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  seedPlanners(7, 5);
  EXPECT_THAT(recorder.lines, ::testing::IsEmpty());
  EXPECT_EQ(ompl::msg::getLogLevel(), ompl::msg::LOG_WARN) << "the caller's level is restored";
  ompl::msg::setLogLevel(level);
  ompl::msg::restorePreviousOutputHandler();
}

TEST_F(Planning, PlansMadeExactlyHaveNothingToVerify) {
  const auto wall = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{.resolution = 0.01, .timeLimit = 5};
  const std::uint64_t callsBefore = wall->callCount();
  const VerifiedPlan plan = planExactly(wall, limits, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  EXPECT_GT(plan.planTime.count(), 0);
  ASSERT_EQ(plan.attempts.size(), 1u);
  EXPECT_EQ(plan.attempts[0].source, wall->name());
  EXPECT_EQ(plan.attempts[0].time, plan.planTime);
  EXPECT_EQ(plan.attempts[0].simplifyTime, plan.simplifyTime);
  EXPECT_EQ(plan.exactChecks, wall->callCount() - callsBefore);
  EXPECT_EQ(plan.attempts[0].checks, plan.exactChecks);
  EXPECT_GT(plan.exactChecks, 0u);
  EXPECT_EQ(plan.relaxedChecks, 0u);
  EXPECT_EQ(plan.verifyTime.count(), 0);
  EXPECT_EQ(plan.repairTime.count(), 0);
  EXPECT_TRUE(checkPath(*wall, plan.path, 0.01).valid());
  const VerifiedPlan blocked = planExactly(wall, limits, vec({0, 0}), kGoal, options);
  EXPECT_EQ(blocked.status, PlanStatus::InvalidStart);
  EXPECT_EQ(blocked.failure, "start in collision");
  EXPECT_THROW(planExactly(nullptr, limits, kStart, kGoal, options), InvalidArgument);
}

// A plan counts every configuration its source answered: the ends, the planner's states and
// edges (up to each edge's first collision), and simplification; for an exact checker that is
// every call it got, and a plan on a model counts alike without calling anything.
TEST_F(Planning, CountsTheConfigurationsItsSourceAnswered) {
  const auto wall = std::make_shared<FunctionChecker>("wall", 2, inWall);
  const JointLimits limits = JointLimits::unitBox(2);
  for (const double simplifyTime : {0.0, 0.1}) {
    const PlannerOptions options{.resolution = 0.01, .timeLimit = 5, .simplifyTime = simplifyTime};
    wall->resetCallCount();
    const PlanResult plan = planMotion(wall, limits, kStart, kGoal, options);
    ASSERT_TRUE(plan.solved());
    EXPECT_EQ(plan.checks, wall->callCount());
    EXPECT_GT(plan.checks, 100u);  // around the wall at 0.01: hundreds of states
  }
  wall->resetCallCount();
  EXPECT_EQ(planMotion(wall, limits, vec({0, 0}), kGoal, {}).checks, 1u);  // the start alone
  EXPECT_EQ(wall->callCount(), 1u);
}

// A plan times its source's answers: with a source that takes 20 µs an answer they are most of
// the plan's time (the planner's own work is a few µs a state), never more than all of it.
TEST_F(Planning, TimesItsSourcesAnswers) {
  const auto slowWall = std::make_shared<FunctionChecker>("slow wall", 2, [](const double* q) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(20);
    while (std::chrono::steady_clock::now() < until) {
    }
    return inWall(q);
  });
  const PlannerOptions options{.resolution = 0.01, .timeLimit = 5, .simplifyTime = 0.1};
  const PlanResult plan = planMotion(slowWall, JointLimits::unitBox(2), kStart, kGoal, options);
  ASSERT_TRUE(plan.solved());
  EXPECT_GE(plan.checkTime, std::chrono::microseconds(20) * plan.checks);
  EXPECT_LE(plan.checkTime, plan.time);
  EXPECT_GT(plan.checkTime.count(), 0.5 * static_cast<double>(plan.time.count()));
  const PlanResult blocked =
      planMotion(slowWall, JointLimits::unitBox(2), vec({0, 0}), kGoal, options);
  EXPECT_EQ(blocked.checks, 1u);  // the start alone, timed too
  EXPECT_GE(blocked.checkTime, std::chrono::microseconds(20));
}

// A source that closes the wall's gap finds nothing in its share of the time; the optimistic
// hybrid after it (its "collides" confirmed by the exact checker) finds the path, which
// verification finds free. Every question the hybrid asked of the exact checker is counted and
// recorded with verification's.
TEST_F(Planning, AnOptimisticHybridReopensWhatItsSourceCloses) {
  const auto exact = std::make_shared<FunctionChecker>("wall", 2, inWall);
  const auto closed = std::make_shared<FunctionChecker>(
      "closed", 2, [](const double* q) { return std::abs(q[0]) < 0.1; });
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{
      .resolution = 0.01, .timeLimit = 2, .verify = {.approximateShare = 0.1}};
  exact->resetCallCount();
  const VerifiedPlan plan =
      planVerifiedOptimistically(closed, exact, limits, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  EXPECT_EQ(plan.plannedOn, "closed&wall");
  ASSERT_EQ(plan.attempts.size(), 2u);
  EXPECT_EQ(plan.attempts[0].status, PlanStatus::Timeout);
  EXPECT_EQ(plan.attempts[1].source, "closed&wall");
  EXPECT_EQ(plan.exactChecks, exact->callCount());
  EXPECT_EQ(plan.exactAnswers.size(), exact->callCount());
  EXPECT_TRUE(checkPath(*exact, plan.path, 0.01).valid());
  EXPECT_THROW(planVerifiedOptimistically(nullptr, exact, limits, kStart, kGoal, options),
               InvalidArgument);
}

TEST_F(Planning, ReportsCollidingEndsAndTimeouts) {
  const auto wall = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{.resolution = 0.01, .timeLimit = 0.2};
  EXPECT_EQ(planMotion(wall, limits, vec({0, 0}), kGoal, options).status, PlanStatus::InvalidStart);
  EXPECT_EQ(planMotion(wall, limits, kStart, vec({0, 0}), options).status, PlanStatus::InvalidGoal);
  // A wall across the whole space: no path exists.
  const auto closed = std::make_shared<FunctionChecker>(
      "closed", 2, [](const double* q) { return std::abs(q[0]) < 0.1; });
  const PlanResult none = planMotion(closed, limits, kStart, kGoal, options);
  EXPECT_EQ(none.status, PlanStatus::Timeout);
  EXPECT_TRUE(none.path.empty());
}

TEST_F(Planning, RefusesBadQueries) {
  const auto wall = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{};
  EXPECT_THAT(
      messageOf<InvalidArgument>([&] { planMotion(wall, limits, vec({0.1}), kGoal, options); }),
      HasSubstr("start"));
  EXPECT_THAT(messageOf<InvalidArgument>([&] {
                planMotion(wall, limits, kStart, vec({0.2, std::nan("")}), options);
              }),
              HasSubstr("goal value [1]"));
  EXPECT_THAT(messageOf<InvalidArgument>([&] {
                planMotion(wall, limits, kStart, vec({0.2, 1.5}), options);
              }),
              HasSubstr("outside the joint limits"));
  EXPECT_THAT(messageOf<InvalidArgument>(
                  [&] { planMotion(wall, JointLimits::unitBox(3), kStart, kGoal, options); }),
              HasSubstr("start"));
  EXPECT_THAT(messageOf<InvalidArgument>(
                  [&] { planMotion(wall, limits, kStart, kGoal, {.resolution = -1}); }),
              HasSubstr("resolution"));
  EXPECT_THAT(messageOf<InvalidArgument>(
                  [&] { planMotion(wall, limits, kStart, kGoal, {.modelResolution = -1}); }),
              HasSubstr("model resolution must be 0"));
  EXPECT_THAT(messageOf<InvalidArgument>([&] {
                planMotion(wall, limits, kStart, kGoal, {.modelResolution = std::nan("")});
              }),
              HasSubstr("model resolution"));
  EXPECT_THAT(messageOf<InvalidArgument>(
                  [&] { planMotion(wall, limits, kStart, kGoal, {.timeLimit = 0}); }),
              HasSubstr("time limit"));
  EXPECT_THAT(messageOf<InvalidArgument>([] { parsePlannerType("PRM"); }), HasSubstr("'PRM'"));
  EXPECT_EQ(parsePlannerType("rrt-connect"), PlannerType::RrtConnect);
  EXPECT_EQ(parsePlannerType("BITstar"), PlannerType::BitStar);
  EXPECT_EQ(parsePlannerType("RRT*"), PlannerType::RrtStar);
  EXPECT_THAT(messageOf<InvalidArgument>([] { parsePathSimplification("smooth"); }),
              HasSubstr("'smooth' (choose full or shortcuts)"));
  for (const PathSimplification s : {PathSimplification::Full, PathSimplification::Shortcuts})
    EXPECT_EQ(parsePathSimplification(simplificationName(s)), s);
  EXPECT_EQ(parsePathSimplification("Shortcuts"), PathSimplification::Shortcuts);
  EXPECT_THROW(makeSpaceInformation(wall, JointLimits::unitBox(3), 0.01), InvalidArgument);
  EXPECT_THAT(messageOf<InvalidArgument>(
                  [&] { planVerified(wall, nullptr, limits, kStart, kGoal, options); }),
              HasSubstr("exact checker is a null pointer"));
  EXPECT_THAT(messageOf<InvalidArgument>([&] {
                verifyAndRepair({kStart, kGoal}, wall, JointLimits::unitBox(3), options);
              }),
              HasSubstr("wall checks 2 joints but the joint limits have 3"));
  EXPECT_THROW(makeSpaceInformation(std::shared_ptr<const Model>(), limits, 0.01), InvalidArgument);
}

TEST_F(Planning, RepairsAWaypointInsideAnObstacle) {
  const auto wall = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{.resolution = 0.01, .timeLimit = 5};
  const JointPath broken{kStart, vec({-0.5, 0.0}), vec({0.0, 0.0}), vec({0.5, 0.0}), kGoal};
  const VerifiedPlan repaired = verifyAndRepair(broken, wall, limits, options);
  ASSERT_TRUE(repaired.solved()) << repaired.failure;
  EXPECT_EQ(repaired.invalidStretches, 1u);
  EXPECT_GT(repaired.repairTime.count(), 0);
  EXPECT_GT(repaired.verifyTime.count(), 0);
  EXPECT_TRUE(repaired.path.front().isApprox(kStart));
  EXPECT_TRUE(repaired.path.back().isApprox(kGoal));
  EXPECT_TRUE(
      pathIsFree(repaired.path, 0.01, [](const Eigen::VectorXd& q) { return inWall(q.data()); }));
  // The valid parts are kept: the path still starts with the first two waypoints, and the
  // invalid edges up to the last free states before the wall (|x| < 0.1) on either side: the
  // bridge joins those, not the waypoints, so it replans only what collided.
  EXPECT_TRUE(repaired.path[1].isApprox(broken[1]));
  const Eigen::VectorXd& before = repaired.path[2];
  EXPECT_NEAR(before[1], 0.0, 1e-12);
  EXPECT_GE(before[0], -0.1 - options.resolution);
  EXPECT_LE(before[0], -0.1);
  const Eigen::VectorXd& after = repaired.path[repaired.path.size() - 3];
  EXPECT_NEAR(after[1], 0.0, 1e-12);
  EXPECT_GE(after[0], 0.1);
  EXPECT_LE(after[0], 0.1 + options.resolution);
  EXPECT_TRUE(repaired.path[repaired.path.size() - 2].isApprox(broken[3]));
}

TEST_F(Planning, RepairsAnEdgeThatCutsACorner) {
  // Both waypoints are free, the straight line between them clips the wall's top corner.
  const auto wall = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{.resolution = 0.005, .timeLimit = 5};
  const JointPath cutting{kStart, vec({-0.15, 0.45}), vec({0.15, 0.55}), kGoal};
  ASSERT_TRUE(checkPath(*wall, {cutting[1]}, 0.005).valid());
  ASSERT_TRUE(checkPath(*wall, {cutting[2]}, 0.005).valid());
  const VerifiedPlan repaired = verifyAndRepair(cutting, wall, limits, options);
  ASSERT_TRUE(repaired.solved()) << repaired.failure;
  EXPECT_EQ(repaired.invalidStretches, 1u);
  EXPECT_TRUE(
      pathIsFree(repaired.path, 0.005, [](const Eigen::VectorXd& q) { return inWall(q.data()); }));
  // A valid path comes back unchanged, with no repair.
  const VerifiedPlan same = verifyAndRepair(repaired.path, wall, limits, options);
  EXPECT_EQ(same.invalidStretches, 0u);
  EXPECT_EQ(same.path.size(), repaired.path.size());
}

TEST_F(Planning, ReplansTheWholeMotionWhenAStretchCannotBeBridged) {
  // The middle waypoint is free but sealed in a ring of obstacle: no stretch reaches it.
  const auto ringed = std::make_shared<FunctionChecker>("ringed", 2, [](const double* q) {
    const double r = std::hypot(q[0] + 0.5, q[1] - 0.5);
    return inWall(q) || (r > 0.1 && r < 0.15);
  });
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{.resolution = 0.01, .timeLimit = 2};
  const VerifiedPlan repaired =
      verifyAndRepair({kStart, vec({-0.5, 0.5}), kGoal}, ringed, limits, options);
  ASSERT_TRUE(repaired.solved()) << repaired.failure;
  EXPECT_TRUE(repaired.wholePathReplanned);
  EXPECT_TRUE(pathIsFree(repaired.path, 0.01, [&](const Eigen::VectorXd& q) {
    return ringed->inCollision(std::span<const double>(q.data(), 2));
  }));
}

// A bridge is searched first within the box its ends span grown by bridgeMargin: a detour within
// the margin is found there, and one beyond it only in the search of the whole joint range after.
TEST_F(Planning, ABridgeIsSearchedFirstWithinItsMargin) {
  std::atomic<int> beyond{0};  // questions about states more than 1.05 from the straight line
  const auto slotted = std::make_shared<FunctionChecker>("slotted", 2, [&](const double* q) {
    if (std::abs(q[1]) > 1.05) ++beyond;
    return std::abs(q[0]) < 0.1 && !(q[1] > 0.7 && q[1] < 0.9);
  });
  const JointLimits limits(vec({-3, -3}), vec({3, 3}));
  const JointPath straight{vec({-1, 0}), vec({1, 0})};
  for (const double margin : {1.0, 0.3}) {
    beyond = 0;
    const PlannerOptions options{
        .resolution = 0.01, .timeLimit = 5, .verify = {.bridgeMargin = margin}};
    const VerifiedPlan repaired = verifyAndRepair(straight, slotted, limits, options);
    ASSERT_TRUE(repaired.solved()) << repaired.failure;
    EXPECT_EQ(repaired.invalidStretches, 1u);
    EXPECT_FALSE(repaired.wholePathReplanned);
    if (margin == 1.0) {
      EXPECT_EQ(beyond, 0) << "the slot lies within the margin";
    } else {
      EXPECT_GT(beyond, 0) << "the slot lies beyond the margin";
    }
  }
  EXPECT_THROW(validate(PlannerOptions{.verify = {.bridgeMargin = -0.1}}), InvalidArgument);
  EXPECT_THROW(validate(PlannerOptions{.verify = {.bridgeMargin = std::nan("")}}), InvalidArgument);
}

TEST_F(Planning, SaysPlainlyWhenNoValidPathIsFound) {
  const auto closed = std::make_shared<FunctionChecker>(
      "closed", 2, [](const double* q) { return std::abs(q[0]) < 0.1; });
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{.resolution = 0.01, .timeLimit = 0.2};
  const VerifiedPlan none =
      verifyAndRepair({kStart, vec({0, 0.9}), kGoal}, closed, limits, options);
  EXPECT_FALSE(none.solved());
  EXPECT_THAT(
      none.failure,
      HasSubstr(
          "could not replan the stretch between waypoints 0 and 2 on closed, nor the whole path"));
  const VerifiedPlan badStart = verifyAndRepair({vec({0, 0}), kGoal}, closed, limits, options);
  EXPECT_EQ(badStart.status, PlanStatus::InvalidStart);
}

/// A Fastron model of the wall world, trained on a grid of exact labels.
std::shared_ptr<const Model> wallModel() {
  const Configurations q = test::uniformPoints(3000, 2, 7);
  Labels y(static_cast<std::size_t>(q.rows()));
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    y[static_cast<std::size_t>(i)] = inWall(q.row(i).data()) ? 1 : -1;
  Trainer trainer(JointLimits::unitBox(2), {.kernel = {.gamma = 30}, .beta = 10});
  trainer.addPoints(q, y);
  trainer.update();
  return trainer.model();
}

TEST_F(Planning, FastronPlansAreVerifiedAndRepairedIntoValidPaths) {
  const auto wall = wallChecker();
  const auto model = wallModel();
  const JointLimits limits = JointLimits::unitBox(2);
  for (const PlannerType type : allPlannerTypes()) {
    const PlannerOptions options{.type = type, .resolution = 0.01, .timeLimit = 10};
    const VerifiedPlan plan = planVerified(model, wall, limits, kStart, kGoal, options);
    ASSERT_TRUE(plan.solved()) << plannerName(type) << ": " << plan.failure;
    EXPECT_GT(plan.planTime.count(), 0);
    EXPECT_TRUE(pathIsFree(plan.path, 0.01, [](const Eigen::VectorXd& q) {
      return inWall(q.data());
    })) << plannerName(type);
  }
}

TEST_F(Planning, ModelsCheckEdgesAtTheirOwnCoarserStepAndVerificationKeepsTheFineOne) {
  const auto wall = wallChecker();
  const auto model = wallModel();
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions fine{.resolution = 0.01};
  EXPECT_EQ(edgeResolution(wall, fine), 0.01);
  EXPECT_DOUBLE_EQ(edgeResolution(model, fine), kModelStepsPerStep * 0.01);
  const auto asChecker = std::make_shared<ModelChecker>(model);
  EXPECT_DOUBLE_EQ(edgeResolution(asChecker, fine), kModelStepsPerStep * 0.01);
  EXPECT_DOUBLE_EQ(
      edgeResolution(std::make_shared<HybridChecker>(model, wall, UncertaintyBand{}), fine),
      kModelStepsPerStep * 0.01);
  EXPECT_DOUBLE_EQ(
      edgeResolution(std::make_shared<AnyOfChecker>(
                         std::vector<std::shared_ptr<const CollisionChecker>>{wall, asChecker}),
                     fine),
      kModelStepsPerStep * 0.01);
  EXPECT_EQ(edgeResolution(std::make_shared<AnyOfChecker>(
                               std::vector<std::shared_ptr<const CollisionChecker>>{wall, wall}),
                           fine),
            0.01);

  // A model step wider than the wall (0.2): the straight motion's states at x = -0.27 and 0.27
  // miss it, so the model lets it pass; at the fine step it does not.
  const PlannerOptions coarse{.resolution = 0.01, .modelResolution = 0.6};
  EXPECT_EQ(edgeResolution(model, coarse), 0.6);
  const auto motionIsValid = [&](double step) {
    const auto si = makeSpaceInformation(model, limits, step);
    ompl::base::ScopedState<> a(si->getStateSpace()), b(si->getStateSpace());
    for (unsigned j = 0; j < 2; ++j) {
      a[j] = kStart[j];
      b[j] = kGoal[j];
    }
    return si->checkMotion(a.get(), b.get());
  };
  EXPECT_TRUE(motionIsValid(edgeResolution(model, coarse)));
  EXPECT_FALSE(motionIsValid(edgeResolution(model, fine)));
  // Whatever the model's step, verification checks the final path at the fine one.
  for (const PlannerOptions& options : {coarse, fine}) {
    const VerifiedPlan plan = planVerified(model, wall, limits, kStart, kGoal, options);
    ASSERT_TRUE(plan.solved()) << plan.failure;
    EXPECT_TRUE(
        pathIsFree(plan.path, 0.01, [](const Eigen::VectorXd& q) { return inWall(q.data()); }));
  }
}

TEST_F(Planning, AnApproximateCheckerWrongAboutAnEndStillPlans) {
  const auto wall = wallChecker();
  const JointLimits limits = JointLimits::unitBox(2);
  // A substitute's plan gets a tenth of the limit: the default share (0.2%) is 1 ms here, which a
  // sanitizer build on a busy machine missed, and the whole motion went to the exact checker.
  const PlannerOptions options{
      .resolution = 0.01, .timeLimit = 0.5, .verify = {.substituteShare = 0.1}};
  // It thinks the start collides, but a step away from it is free: the plan is made on it from
  // a substitute that the exact checker reaches from the true start in a straight line, so the
  // first edge needs no repair.
  const auto nearStart = std::make_shared<const FunctionChecker>(
      "near-start", 2, [](const double* q) { return q[0] < -0.7 || inWall(q); });
  const VerifiedPlan substituted = planVerified(nearStart, wall, limits, kStart, kGoal, options);
  ASSERT_TRUE(substituted.solved()) << substituted.failure;
  EXPECT_TRUE(substituted.substituteEnds);
  EXPECT_FALSE(substituted.wholePathReplanned);
  EXPECT_EQ(substituted.invalidStretches, 0u);
  EXPECT_EQ(substituted.path.front(), kStart);
  EXPECT_TRUE(pathIsFree(substituted.path, 0.01,
                         [](const Eigen::VectorXd& q) { return inWall(q.data()); }));
  // It thinks everything left of x = 0.85 collides, farther from the start than the substitute
  // search reaches (1.6): the whole motion is planned on the exact checker.
  const auto wide = std::make_shared<const FunctionChecker>(
      "wide", 2, [](const double* q) { return q[0] < 0.85 || inWall(q); });
  const VerifiedPlan fallback = planVerified(wide, wall, limits, kStart, kGoal, options);
  ASSERT_TRUE(fallback.solved()) << fallback.failure;
  EXPECT_TRUE(fallback.wholePathReplanned);
  EXPECT_TRUE(
      pathIsFree(fallback.path, 0.01, [](const Eigen::VectorXd& q) { return inWall(q.data()); }));
  // A model, trained on the wall, that predicts a collision at a start just beside it (at some
  // height: where its boundary bulges out depends on its support points).
  const auto model = wallModel();
  Eigen::VectorXd beside = vec({-0.2, -0.9});
  for (; beside[1] < 0.4; beside[1] += 0.1) {
    for (beside[0] = -0.2; beside[0] < -0.1 && !model->inCollision(beside.data());)
      beside[0] += 0.001;
    if (beside[0] < -0.1) break;
  }
  ASSERT_LT(beside[0], -0.1) << "the model predicts no collision beside the wall";
  const VerifiedPlan fromModel = planVerified(model, wall, limits, beside, kGoal, options);
  ASSERT_TRUE(fromModel.solved()) << fromModel.failure;
  EXPECT_TRUE(fromModel.substituteEnds);
  EXPECT_TRUE(
      pathIsFree(fromModel.path, 0.01, [](const Eigen::VectorXd& q) { return inWall(q.data()); }));
}

TEST_F(Planning, APlansTimeCountsItsSearchForSubstituteEnds) {
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{
      .resolution = 0.01, .timeLimit = 0.5, .verify = {.substituteShare = 0.1}};
  // The exact checker's first three answers take 20 ms each: the ends' checks and the first state
  // of a straight motion to a substitute, all asked while substitutes are searched.
  auto answered = std::make_shared<std::atomic<int>>(0);
  const auto slowAtFirst =
      std::make_shared<const FunctionChecker>("slow at first", 2, [answered](const double* q) {
        if (answered->fetch_add(1) < 3) std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return inWall(q);
      });
  const auto nearStart = std::make_shared<const FunctionChecker>(
      "near-start", 2, [](const double* q) { return q[0] < -0.7 || inWall(q); });
  const VerifiedPlan plan = planVerified(nearStart, slowAtFirst, limits, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  ASSERT_TRUE(plan.substituteEnds);
  ASSERT_FALSE(plan.attempts.empty());
  EXPECT_EQ(plan.attempts.front().source, "near-start");
  EXPECT_GE(plan.attempts.front().time, std::chrono::milliseconds(60));
  EXPECT_GE(plan.planTime, std::chrono::milliseconds(60));
}

TEST_F(Planning, APlansChecksCountTheApproximateAnswersOfItsSearchForSubstituteEnds) {
  // Every answer of the approximate checker is asked within the one attempt on it: the first
  // plan (refused at the start), the search for substitute ends and the plan between them.
  const JointLimits limits = JointLimits::unitBox(2);
  const PlannerOptions options{
      .resolution = 0.01, .timeLimit = 0.5, .verify = {.substituteShare = 0.1}};
  const auto exact = std::make_shared<const FunctionChecker>("wall", 2, inWall);
  const auto nearStart = std::make_shared<const FunctionChecker>(
      "near-start", 2, [](const double* q) { return q[0] < -0.7 || inWall(q); });
  const VerifiedPlan plan = planVerified(nearStart, exact, limits, kStart, kGoal, options);
  ASSERT_TRUE(plan.solved()) << plan.failure;
  ASSERT_TRUE(plan.substituteEnds);
  ASSERT_EQ(plan.attempts.size(), 1u);
  EXPECT_EQ(plan.attempts.front().checks, nearStart->callCount());
  EXPECT_GT(plan.attempts.front().checkTime, std::chrono::nanoseconds(0));
}

TEST_F(Planning, BaxterPathsAreFreeUnderFclAtATenTimesFinerResolution) {
  // Planning checks states 0.01 rad apart (Euclidean) with Baxter padded by 3 cm. Between two
  // checked states no point of the arm is farther than 2 cm from where it was at one of them
  // (|dp| <= |dq|_1 r <= sqrt(7) |dq| r, every point within r = 1.5 m of every joint axis), so the
  // bare arm never reaches an obstacle: the final paths, Fastron's verified and repaired among
  // them, must be free under the unpadded FCL checked every 0.001 rad, by code independent of the
  // planners' own checks.
  Robot baxter = loadRobot("baxter");
  const Scene scene = loadScene(dataDirectory() / "scenes" / "baxter_three_boxes.yaml");
  const auto padded =
      std::make_shared<const FclChecker>(baxter, scene, CheckerOptions{.padding = 0.03});
  const FclChecker bare(baxter, scene);
  const JointLimits limits = baxter.limits();
  Rng rng(3);
  const Configurations q = uniformConfigurations(limits, 400, rng);
  std::vector<Eigen::VectorXd> free;
  for (Eigen::Index i = 0; i < q.rows() && free.size() < 4; ++i) {
    if (!padded->inCollision(std::span<const double>(q.row(i).data(), limits.dim()))) {
      free.emplace_back(q.row(i).transpose());
    }
  }
  ASSERT_EQ(free.size(), 4u);
  ProxyCollisionDetector proxy(padded, limits,
                               {.train = {.kernel = {.gamma = 5}, .beta = 500}, .seed = 2});
  proxy.initialize(1500);
  const auto collidesUnderFcl = [&](const Eigen::VectorXd& x) {
    return bare.inCollision(std::span<const double>(x.data(), limits.dim()));
  };
  for (const PlannerType type : {PlannerType::RrtConnect, PlannerType::BitStar}) {
    const PlannerOptions options{.type = type, .resolution = 0.01, .timeLimit = 20};
    const PlanResult exact = planMotion(padded, limits, free[0], free[1], options);
    ASSERT_TRUE(exact.solved()) << plannerName(type) << ": " << toString(exact.status);
    EXPECT_TRUE(pathIsFree(exact.path, 0.001, collidesUnderFcl)) << plannerName(type);
    const VerifiedPlan verified =
        planVerified(proxy.model(), padded, limits, free[2], free[3], options);
    ASSERT_TRUE(verified.solved()) << plannerName(type) << ": " << verified.failure;
    EXPECT_TRUE(pathIsFree(verified.path, 0.001, collidesUnderFcl)) << plannerName(type);
  }
}

}  // namespace
}  // namespace fastron
