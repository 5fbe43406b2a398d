// Time per exact check for each shipped robot: forward kinematics alone, FK + FCL, FK + GJK,
// against 1, 3, 10, 30 and 100 obstacles; FCL with its clearance bounds first (bounds:1, the
// default) and with its broad phase alone (bounds:0). Compare within a run
// (scripts/bench_table.py).

#include <benchmark/benchmark.h>

#include <algorithm>

#include "fastron/core/active_learning.h"
#include "fastron/core/simd.h"
#include "fastron/core/trainer.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/point_kinematics.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"

namespace fastron {
namespace {

const std::vector<std::string> kRobots{"rod2",  "rod4", "baxter",      "ur3",
                                       "panda", "psm",  "gripper-arm", "mobile-arm"};

// n boxes of 0.1 m, each within 0.25 m of a moving link of the robot at a random
// configuration, and none touching the robot's fixed geometry (which would put every
// configuration in collision). Seeded.
Scene boxesNearTheRobot(const Robot& robot, std::size_t n) {
  Rng rng(11);
  KinematicsData a = makeKinematicsData(robot), b = makeKinematicsData(robot);
  const Configurations two = uniformConfigurations(robot.limits(), 2, rng);
  forwardKinematics(robot, two.row(0).data(), a);
  forwardKinematics(robot, two.row(1).data(), b);
  std::vector<std::size_t> moving;
  std::vector<ConvexBody> fixed;
  for (std::size_t s = 0; s < robot.shapes().size(); ++s) {
    if (shapePose(robot, a, s).isApprox(shapePose(robot, b, s))) {
      fixed.push_back(ConvexBody::from(robot.shapes()[s].shape));
      fixed.back().pose = shapePose(robot, a, s);
    } else {
      moving.push_back(s);
    }
  }
  std::uniform_real_distribution<double> offset(-0.25, 0.25);
  std::uniform_int_distribution<std::size_t> pick(0, moving.size() - 1);
  Scene scene;
  while (scene.size() < n) {
    const Configurations q = uniformConfigurations(robot.limits(), 1, rng);
    forwardKinematics(robot, q.data(), a);
    const Eigen::Vector3d near = shapePose(robot, a, moving[pick(rng)]).translation();
    const Box box{Eigen::Vector3d::Constant(0.1)};
    ConvexBody body = ConvexBody::from(box);
    body.pose = makePose(near + Eigen::Vector3d(offset(rng), offset(rng), offset(rng)));
    bool touchesFixed = false;
    for (const ConvexBody& f : fixed) touchesFixed = touchesFixed || gjkIntersect(body, f);
    if (!touchesFixed)
      scene.add({"box" + std::to_string(scene.size()), box, body.pose, std::nullopt});
  }
  return scene;
}

Configurations queries(const Robot& robot) {
  Rng rng(12);
  return uniformConfigurations(robot.limits(), 1024, rng);
}

void BM_ForwardKinematics(benchmark::State& state) {
  const Robot robot = loadRobot(kRobots[static_cast<std::size_t>(state.range(0))]);
  const Configurations q = queries(robot);
  KinematicsData data = makeKinematicsData(robot);
  std::size_t i = 0;
  for (auto _ : state) {
    forwardKinematics(robot, q.row(static_cast<Eigen::Index>(i)).data(), data);
    benchmark::DoNotOptimize(data.linkPoses.data());
    i = (i + 1) % 1024;
  }
  state.SetLabel(robot.name());
}
BENCHMARK(BM_ForwardKinematics)->DenseRange(0, 7)->ArgName("robot");

// Task-space features: the world positions of the robot's automatic control points (at most
// `points` of them), float path (queries) and double path (training).
template <class T>
void BM_ControlPoints(benchmark::State& state) {
  const Robot robot = loadRobot(kRobots[static_cast<std::size_t>(state.range(0))]);
  const RobotPointKinematics kinematics(
      robot, defaultControlPoints(robot, {.maxPoints = static_cast<std::size_t>(state.range(1))}));
  const Configurations q = queries(robot);
  std::vector<T> out(3 * kinematics.pointCount());
  std::size_t i = 0;
  for (auto _ : state) {
    kinematics.positions(q.row(static_cast<Eigen::Index>(i)).data(), out.data());
    benchmark::DoNotOptimize(out.data());
    i = (i + 1) % 1024;
  }
  state.SetLabel(robot.name() + ", " + std::to_string(kinematics.pointCount()) + " points, " +
                 std::to_string(kinematics.steps()) + " joints");
}
BENCHMARK(BM_ControlPoints<float>)
    ->ArgsProduct({{2, 3, 4, 5}, {1, 3, 6, 0}})
    ->ArgNames({"robot", "points"});
BENCHMARK(BM_ControlPoints<double>)->ArgsProduct({{2, 4}, {3}})->ArgNames({"robot", "points"});

// The same float positions for a batch of `batch` configurations at once (an edge check's
// states), sixteen per pass with one configuration per SIMD lane; time per configuration.
void BM_ControlPointsBatch(benchmark::State& state) {
  const Robot robot = loadRobot(kRobots[static_cast<std::size_t>(state.range(0))]);
  const RobotPointKinematics kinematics(
      robot, defaultControlPoints(robot, {.maxPoints = static_cast<std::size_t>(state.range(1))}));
  const auto batch = static_cast<std::size_t>(state.range(2));
  const Configurations q = queries(robot);
  std::vector<float> out(3 * kinematics.pointCount() * batch);
  std::size_t i = 0;
  for (auto _ : state) {
    kinematics.positionsBatch(q.row(static_cast<Eigen::Index>(i)).data(), batch, out.data());
    benchmark::DoNotOptimize(out.data());
    i = (i + batch) % (1024 - batch);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(batch));
  state.SetLabel(robot.name() + ", " + std::to_string(kinematics.pointCount()) + " points");
}
BENCHMARK(BM_ControlPointsBatch)
    ->ArgsProduct({{2, 4}, {4}, {2, 3, 4, 16, 64}})
    ->ArgNames({"robot", "points", "batch"});

// A whole task-space query on Baxter (4 automatic control points): |S| random support
// configurations with random weights. batch 1: Model::score one configuration at a time;
// batch 16: Model::scoreBatch (features for sixteen at once, kernel sums four per pass), the
// path of edge checks. terms 1: the default kernel for task space (a term per control point and
// the whole vector's); terms 0: one term (gamma 40). Time per configuration.
void BM_TaskSpaceQuery(benchmark::State& state) {
  const Robot robot = loadRobot("baxter");
  const auto support = static_cast<std::size_t>(state.range(0));
  const auto batch = static_cast<std::size_t>(state.range(1));
  const bool pointTerms = state.range(2) != 0;
  Rng rng(13);
  const Model model(robotFeatures(robot, FeatureKind::Kinematic),
                    pointTerms ? defaultTrainParams(FeatureKind::Kinematic).kernel
                               : Kernel{KernelType::RationalQuadratic, 40},
                    uniformConfigurations(robot.limits(), support, rng),
                    Eigen::VectorXd::Random(static_cast<Eigen::Index>(support)));
  const Configurations q = queries(robot);
  std::vector<double> out(batch);
  std::size_t i = 0;
  for (auto _ : state) {
    const double* rows = q.row(static_cast<Eigen::Index>(i)).data();
    if (batch == 1) {
      benchmark::DoNotOptimize(model.score(rows));
    } else {
      model.scoreBatch(rows, batch, out.data());
      benchmark::DoNotOptimize(out.data());
    }
    i = (i + batch) % (1024 - batch);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(batch));
  state.SetLabel("baxter, " + std::to_string(model.featureDim() / 3) + " points, " +
                 std::string(toString(activeSimdPath())));
}

// The same on one SIMD path of the kernel sums (simd: 0 portable, 1 AVX2, 2 AVX-512; simd.h).
void BM_TaskSpaceQueryOnSimdPath(benchmark::State& state) {
  const auto path = static_cast<SimdPath>(state.range(3));
  const std::vector<SimdPath> supported = supportedSimdPaths();
  if (std::find(supported.begin(), supported.end(), path) == supported.end()) {
    state.SkipWithError("this processor cannot run this SIMD path");
    return;
  }
  const SimdPath saved = activeSimdPath();
  useSimdPath(path);
  BM_TaskSpaceQuery(state);
  useSimdPath(saved);
}
BENCHMARK(BM_TaskSpaceQuery)
    ->ArgsProduct({{100, 250, 300, 450, 1000}, {1, 16}, {0, 1}})
    ->ArgNames({"S", "batch", "terms"});
BENCHMARK(BM_TaskSpaceQueryOnSimdPath)
    ->ArgsProduct({{300, 1000}, {1, 16}, {0, 1}, {0, 1, 2}})
    ->ArgNames({"S", "batch", "terms", "simd"});

// Model::scoreGradients (analytic: the kernel's derivative, summed in float on the SIMD path in
// use, through the points' Jacobian) against Model::scoreBatch on the same 16 configurations of
// the same task-space model (Baxter, the default kernel): gradient 0 times the scores, 1 the
// scores and gradients. Time per batch of 16.
void BM_ScoreGradientBatch(benchmark::State& state) {
  const Robot robot = loadRobot("baxter");
  const auto support = static_cast<std::size_t>(state.range(0));
  const bool gradient = state.range(1) != 0;
  Rng rng(13);
  const Model model(robotFeatures(robot, FeatureKind::Kinematic),
                    defaultTrainParams(FeatureKind::Kinematic).kernel,
                    uniformConfigurations(robot.limits(), support, rng),
                    Eigen::VectorXd::Random(static_cast<Eigen::Index>(support)));
  constexpr std::size_t kBatch = 16;
  const Configurations q = queries(robot).topRows(kBatch);
  std::vector<double> out(kBatch);
  for (auto _ : state) {
    if (gradient) {
      benchmark::DoNotOptimize(model.scoreGradients(q));
    } else {
      model.scoreBatch(q.data(), kBatch, out.data());
      benchmark::DoNotOptimize(out.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kBatch));
}
BENCHMARK(BM_ScoreGradientBatch)->ArgsProduct({{300, 1000}, {0, 1}})->ArgNames({"S", "gradient"});

template <class Checker>
void BM_Check(benchmark::State& state) {
  const Robot robot = loadRobot(kRobots[static_cast<std::size_t>(state.range(0))]);
  const auto obstacles = static_cast<std::size_t>(state.range(1));
  const Checker checker(robot, boxesNearTheRobot(robot, obstacles),
                        {.proveMotionsFree = state.range(2) != 0});
  const Configurations q = queries(robot);
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    hits += checker.inCollision({q.row(static_cast<Eigen::Index>(i)).data(), robot.dof()});
    i = (i + 1) % 1024;
  }
  state.SetLabel(robot.name());
  state.counters["in_collision"] =
      static_cast<double>(hits) / static_cast<double>(state.iterations());
}

// The same, on configurations FCL finds free only: no early exit at a first contact, so every
// obstacle near a link must be ruled out (the cost a broad phase is for).
template <class Checker>
void BM_CheckFree(benchmark::State& state) {
  const Robot robot = loadRobot(kRobots[static_cast<std::size_t>(state.range(0))]);
  const Scene scene = boxesNearTheRobot(robot, static_cast<std::size_t>(state.range(1)));
  const Checker checker(robot, scene, {.proveMotionsFree = state.range(2) != 0});
  const FclChecker reference(robot, scene);
  Rng rng(13);
  const Configurations pool = uniformConfigurations(robot.limits(), 16384, rng);
  std::vector<Eigen::Index> free;
  for (Eigen::Index i = 0; i < pool.rows(); ++i) {
    if (!reference.inCollision({pool.row(i).data(), robot.dof()})) free.push_back(i);
  }
  if (free.empty()) {
    state.SkipWithError("no free configuration among 16384 samples");
    return;
  }
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(checker.inCollision({pool.row(free[i]).data(), robot.dof()}));
    i = (i + 1) % free.size();
  }
  state.SetLabel(robot.name());
  state.counters["free_share"] =
      static_cast<double>(free.size()) / static_cast<double>(pool.rows());
}

void robotsAndObstacles(benchmark::internal::Benchmark* b) {
  b->ArgsProduct({{0, 1, 2, 3, 4, 5}, {1, 3, 10, 30, 100}, {0}})
      ->ArgNames({"robot", "obstacles", "bounds"});
}
void robotsObstaclesAndBounds(benchmark::internal::Benchmark* b) {
  b->ArgsProduct({{0, 1, 2, 3, 4, 5}, {1, 3, 10, 30, 100}, {0, 1}})
      ->ArgNames({"robot", "obstacles", "bounds"});
}
BENCHMARK(BM_Check<FclChecker>)->Apply(robotsObstaclesAndBounds);
BENCHMARK(BM_Check<GjkChecker>)->Apply(robotsAndObstacles);
BENCHMARK(BM_CheckFree<FclChecker>)->Apply(robotsObstaclesAndBounds);
BENCHMARK(BM_CheckFree<GjkChecker>)->Apply(robotsAndObstacles);

}  // namespace
}  // namespace fastron
