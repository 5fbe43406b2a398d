// Time per planning query on Baxter's 7-joint arm among three boxes (RRT-Connect and BIT*, 0.03 rad
// edges, paths simplified): on a task-space Fastron model alone, on FCL alone, and Fastron
// verified and repaired with FCL. Twenty fixed queries between configurations both checkers find
// free; compare within a run. Also the exact check of the final paths, serial and parallel.

#include <benchmark/benchmark.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <map>

#include "fastron/core/active_learning.h"
#include "fastron/core/metrics.h"
#include "fastron/experiments/problem_families.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/pipeline/self_pair_tables.h"
#include "fastron/planning/parallel_check.h"
#include "fastron/planning/planner.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/labelling.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron {
namespace {

struct BaxterQueries {
  JointLimits limits;
  std::shared_ptr<const FclChecker> fcl;
  std::shared_ptr<const Model> model;
  ConfusionCounts accuracy;  ///< of the model against FCL on 2000 fresh uniform configurations
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> queries;
};

const BaxterQueries& baxterQueries() {
  static const BaxterQueries setup = [] {
    ompl::msg::noOutputHandler();
    BaxterQueries b;
    const Robot baxter = loadRobot("baxter");
    b.limits = baxter.limits();
    b.fcl = std::make_shared<const FclChecker>(
        baxter, loadScene(dataDirectory() / "scenes" / "baxter_three_boxes.yaml"));
    ProxyParams params;
    params.train = defaultTrainParams(FeatureKind::Kinematic);
    ProxyCollisionDetector proxy(b.fcl, robotFeatures(baxter, FeatureKind::Kinematic), params);
    proxy.initialize(3000);
    for (int i = 0; i < 3; ++i) proxy.step();
    b.model = proxy.model();
    Rng testRng(6);  // its own draws: the queries below stay those of rng(5)
    const Configurations test = uniformConfigurations(b.limits, 2000, testRng);
    b.accuracy = evaluate(*b.model, test, labelConfigurations(*b.fcl, test));
    Rng rng(5);
    const Configurations q = uniformConfigurations(b.limits, 400, rng);
    std::vector<Eigen::VectorXd> free;
    for (Eigen::Index i = 0; i < q.rows() && free.size() < 40; ++i) {
      if (!b.fcl->inCollision(std::span<const double>(q.row(i).data(), b.limits.dim())) &&
          !b.model->inCollision(q.row(i).data())) {
        free.emplace_back(q.row(i).transpose());
      }
    }
    for (std::size_t i = 0; i + 1 < free.size(); i += 2)
      b.queries.emplace_back(free[i], free[i + 1]);
    return b;
  }();
  return setup;
}

const PlannerOptions kOptions{.type = PlannerType::RrtConnect, .resolution = 0.03, .timeLimit = 10};

/// kOptions with the planner of the benchmark's argument (0: RRT-Connect, 1: BIT*).
PlannerOptions optionsFor(const benchmark::State& state) {
  PlannerOptions options = kOptions;
  options.type = state.range(0) == 0 ? PlannerType::RrtConnect : PlannerType::BitStar;
  return options;
}

template <class Plan>
void runQueries(benchmark::State& state, Plan&& plan) {
  const BaxterQueries& b = baxterQueries();
  const PlannerOptions options = optionsFor(state);
  state.SetLabel(plannerName(options.type));
  std::size_t i = 0, failed = 0;
  for (auto _ : state) {
    const auto& [start, goal] = b.queries[i];
    failed += plan(b, start, goal, options) ? 0 : 1;
    i = (i + 1) % b.queries.size();
  }
  state.counters["failed"] = static_cast<double>(failed);
  // The model beside its speed.
  state.counters["support"] = static_cast<double>(b.model->supportCount());
  state.counters["accuracy"] = b.accuracy.accuracy();
  state.counters["tpr"] = b.accuracy.tpr();
}

void BM_PlanOnFastron(benchmark::State& state) {
  runQueries(state, [](const BaxterQueries& b, const auto& start, const auto& goal,
                       const PlannerOptions& options) {
    return planMotion(b.model, b.limits, start, goal, options).solved();
  });
}

void BM_PlanOnFcl(benchmark::State& state) {
  runQueries(state, [](const BaxterQueries& b, const auto& start, const auto& goal,
                       const PlannerOptions& options) {
    return planMotion(b.fcl, b.limits, start, goal, options).solved();
  });
}

void BM_PlanOnFastronVerifiedWithFcl(benchmark::State& state) {
  runQueries(state, [](const BaxterQueries& b, const auto& start, const auto& goal,
                       const PlannerOptions& options) {
    return planVerified(b.model, b.fcl, b.limits, start, goal, options).solved();
  });
}

// The exact check of each query's path planned on FCL (valid: every state is checked), with
// checkPath (threads 0 here) or checkPathParallel on 1 or 2 threads.
void BM_CheckPath(benchmark::State& state) {
  const BaxterQueries& b = baxterQueries();
  static const std::vector<JointPath> paths = [&] {
    std::vector<JointPath> out;
    for (const auto& [start, goal] : b.queries) {
      out.push_back(planMotion(b.fcl, b.limits, start, goal, kOptions).path);
    }
    return out;
  }();
  const auto threads = static_cast<unsigned>(state.range(0));
  std::size_t i = 0, invalid = 0;
  for (auto _ : state) {
    const PathCheck check = threads == 0
                                ? checkPath(*b.fcl, paths[i], kOptions.resolution)
                                : checkPathParallel(*b.fcl, paths[i], kOptions.resolution, threads);
    invalid += check.valid() ? 0 : 1;
    i = (i + 1) % paths.size();
  }
  state.counters["invalid"] = static_cast<double>(invalid);
}
BENCHMARK(BM_CheckPath)->Arg(0)->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kMicrosecond);

/// Paths to verify on a robot's generated cage problems, with three exact checkers (every state,
/// proofs, proofs with self-pair tables): each problem's path planned on FCL as found and
/// simplified (free), and its straight line from start to goal (mostly colliding).
struct VerificationPaths {
  std::shared_ptr<const FclChecker> dense, certified;
  std::shared_ptr<FclChecker> tables;  // built once (11 s on the mesh Panda), moved scene to scene
  std::vector<JointPath> paths;
  std::size_t states = 0, invalid = 0;
  bool sameVerdicts = true;  ///< the three checkers agree on every path
};

const VerificationPaths& verificationPaths(const std::string& robotName) {
  static std::map<std::string, VerificationPaths> cache;
  if (const auto kept = cache.find(robotName); kept != cache.end()) return kept->second;
  ompl::msg::noOutputHandler();
  seedPlanners(1, 0);  // the same paths in every run
  const Robot robot = loadRobot(robotName);
  experiments::ProblemOptions cages;
  cages.count = 4;
  const auto problems = experiments::generateProblems(robot, cages);
  VerificationPaths v;
  for (const auto& problem : problems) {
    // One scene per problem: the checkers of the last one are kept; earlier paths are checked on
    // their own scene below, before the next replaces it.
    auto dense = std::make_shared<FclChecker>(
        robot, problem.scene, CheckerOptions{.selfCollision = true, .proveMotionsFree = false});
    auto certified =
        std::make_shared<FclChecker>(robot, problem.scene, CheckerOptions{.selfCollision = true});
    // The tables depend on the robot alone: read from the cache (built the first time, as
    // `fastron plan` does), with the first scene, then moved to the next.
    if (v.tables) {
      v.tables->setScene(problem.scene);
    } else {
      v.tables = std::make_shared<FclChecker>(
          robot, problem.scene,
          CheckerOptions{.selfCollision = true,
                         .selfPairTables = pipeline::selfPairTables(robot).tables});
    }
    const Eigen::VectorXd start = Eigen::Map<const Eigen::VectorXd>(
        problem.start.data(), static_cast<Eigen::Index>(problem.start.size()));
    const Eigen::VectorXd goal = Eigen::Map<const Eigen::VectorXd>(
        problem.goal.data(), static_cast<Eigen::Index>(problem.goal.size()));
    PlannerOptions options = kOptions;
    options.simplifyTime = 0;
    const JointPath found = planMotion(dense, robot.limits(), start, goal, options).path;
    options.simplifyTime = 0.1;
    const JointPath simplified = planMotion(dense, robot.limits(), start, goal, options).path;
    for (const JointPath& path : {found, simplified, JointPath{start, goal}}) {
      if (path.empty()) continue;
      const PathCheck a = checkPathParallel(*dense, path, kOptions.resolution, 1);
      const PathCheck b = checkPathParallel(*certified, path, kOptions.resolution, 1);
      const PathCheck c = checkPathParallel(*v.tables, path, kOptions.resolution, 1);
      v.sameVerdicts = v.sameVerdicts && a.invalidWaypoints == b.invalidWaypoints &&
                       a.invalidEdges == b.invalidEdges &&
                       a.invalidWaypoints == c.invalidWaypoints && a.invalidEdges == c.invalidEdges;
    }
    v.dense = dense;
    v.certified = certified;
  }
  // Timed on the last problem's scene: its paths only.
  const auto& last = problems.back();
  const Eigen::VectorXd start = Eigen::Map<const Eigen::VectorXd>(
      last.start.data(), static_cast<Eigen::Index>(last.start.size()));
  const Eigen::VectorXd goal = Eigen::Map<const Eigen::VectorXd>(
      last.goal.data(), static_cast<Eigen::Index>(last.goal.size()));
  PlannerOptions options = kOptions;
  for (const double simplify : {0.0, 0.1}) {
    options.simplifyTime = simplify;
    for (int run = 0; run < 3; ++run) {
      v.paths.push_back(planMotion(v.dense, robot.limits(), start, goal, options).path);
    }
  }
  v.paths.push_back({start, goal});
  for (const JointPath& path : v.paths) {
    v.states += statesAlongPath(path, kOptions.resolution).rows();
    v.invalid += checkPath(*v.dense, path, kOptions.resolution).valid() ? 0 : 1;
  }
  return cache.emplace(robotName, std::move(v)).first->second;
}

const std::vector<std::string> kVerifiedRobots{"panda-mesh", "gripper-arm", "mobile-arm", "panda"};

// Verification of paths on generated cage problems (verify_repair's check, one thread): every
// state checked (certified 0), or the states clearance bounds do not prove free (certified 1; 2:
// with the robot's tables of the distance of self pairs of meshes, pipeline::selfPairTables).
// `same_verdicts` is 1 when both checks agree on every path of four problems.
void BM_VerifyPath(benchmark::State& state) {
  const VerificationPaths& v =
      verificationPaths(kVerifiedRobots[static_cast<std::size_t>(state.range(0))]);
  const FclChecker& checker = state.range(1) == 0   ? *v.dense
                              : state.range(1) == 1 ? *v.certified
                                                    : *v.tables;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(checkPathParallel(checker, v.paths[i], kOptions.resolution, 1));
    i = (i + 1) % v.paths.size();
  }
  state.SetLabel(kVerifiedRobots[static_cast<std::size_t>(state.range(0))]);
  state.counters["states_per_path"] =
      static_cast<double>(v.states) / static_cast<double>(v.paths.size());
  state.counters["invalid_paths"] = static_cast<double>(v.invalid);
  state.counters["same_verdicts"] = v.sameVerdicts ? 1 : 0;
}
BENCHMARK(BM_VerifyPath)
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}})
    ->Args({0, 2})  // the mesh Panda's self pairs of meshes with tables (the others have none)
    ->ArgNames({"robot", "certified"})
    ->Unit(benchmark::kMicrosecond);

// Labels of a scene model's samples (labelConfigurations on one thread; FCL without
// self-collision, as trainSceneModel asks them, or with it, self 1): 2500 uniform configurations in
// the first generated problem of a family, with FCL's broad phase alone (bounds 0) or clearance
// bounds first (bounds 1, the default; 2: and the robot's self-pair tables,
// pipeline::selfPairTables, as the commands read them with --self-collision). `same_labels` is 1
// when both label every configuration alike.
void BM_LabelScene(benchmark::State& state) {
  const std::string robotName = kVerifiedRobots[static_cast<std::size_t>(state.range(0))];
  const Robot robot = loadRobot(robotName);
  experiments::ProblemOptions options;
  options.family =
      state.range(1) == 0 ? experiments::ProblemFamily::Box : experiments::ProblemFamily::Cage;
  options.count = 1;
  const Scene scene = experiments::generateProblems(robot, options).front().scene;
  const bool self = state.range(3) != 0;
  const FclChecker checker(
      robot, scene,
      {.selfCollision = self,
       .proveMotionsFree = state.range(2) != 0,
       .selfPairTables = state.range(2) == 2 ? pipeline::selfPairTables(robot).tables : nullptr});
  const FclChecker broadPhase(robot, scene, {.selfCollision = self, .proveMotionsFree = false});
  Rng rng(3);
  const Configurations q = uniformConfigurations(robot.limits(), 2500, rng);
  const Labels expected = labelConfigurations(broadPhase, q, 1);
  Labels labels;
  for (auto _ : state) labels = labelConfigurations(checker, q, 1);
  state.SetLabel(robotName + (state.range(1) == 0 ? " box" : " cage"));
  state.SetItemsProcessed(state.iterations() * q.rows());
  state.counters["colliding"] = static_cast<double>(std::ranges::count(expected, std::int8_t{1})) /
                                static_cast<double>(q.rows());
  state.counters["same_labels"] = labels == expected ? 1 : 0;
}
BENCHMARK(BM_LabelScene)
    ->ArgsProduct({{0, 1, 2}, {0, 1}, {0, 1}, {0}})  // the Panda of primitives reaches into no box
    ->ArgsProduct({{0, 1, 2}, {0}, {0, 1}, {1}})
    ->ArgsProduct({{0}, {0, 1}, {2}, {1}})  // the mesh Panda's self pairs read from its tables
    ->Args({0, 1, 0, 1})
    ->Args({0, 1, 1, 1})
    ->ArgNames({"robot", "cage", "bounds", "self"})
    ->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_PlanOnFastron)->Arg(0)->Arg(1)->ArgName("bitstar")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PlanOnFcl)->Arg(0)->Arg(1)->ArgName("bitstar")->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PlanOnFastronVerifiedWithFcl)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("bitstar")
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fastron
