// fastron bench NAME: one of the paper's experiments; raw results as CSV, the paper's tables as
// Markdown with the paper's values beside ours, and the paper's figures as PNG.

#include <ompl/util/RandomNumbers.h>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/error.h"
#include "fastron/experiments/changing_experiment.h"
#include "fastron/experiments/cspace_experiment.h"
#include "fastron/experiments/motion_bench_experiment.h"
#include "fastron/experiments/planning_experiment.h"
#include "fastron/experiments/shelf_experiment.h"
#include "fastron/experiments/static_experiment.h"
#include "fastron/experiments/surgical_experiment.h"
#include "plotting.h"
#include "robot_options.h"

namespace fastron::cli {
namespace {

struct BenchOptions {
  std::string name, out, problems, features = "fk";
  std::size_t trials = 0;                    // 0: the experiment's default
  double timeLimit = 0, resolution = 0;      // 0: the experiment's default
  double simplifyTime = -1;                  // < 0: the experiment's default
  double gamma = 0, beta = 0, variance = 0;  // changing only; 0: the default
  std::uint64_t seed = 1;
  bool quick = false, plot = true;
  RobotOptions robot;                  // motion-bench only (default: panda)
  bool selfCollision = false;          // motion-bench only
  std::size_t queriesPerScene = 1;     // motion-bench only
  bool selfModel = false;              // motion-bench only
  bool learnFromVerification = false;  // motion-bench only
};

int runBench(const BenchOptions& o) {
  const std::filesystem::path dir = o.out.empty()
                                        ? std::filesystem::path("fastron-results") / o.name
                                        : std::filesystem::path(o.out);
  if ((o.gamma > 0 || o.beta > 0 || o.variance > 0) && o.name != "changing") {
    throw InvalidArgument("--gamma, --beta and --al-variance go with the changing experiment");
  }
  if ((o.robot.robot != "panda" || !o.robot.packagePaths.empty() || !o.robot.srdf.empty() ||
       o.selfCollision || o.queriesPerScene != 1 || o.selfModel || o.learnFromVerification) &&
      o.name != "motion-bench") {
    throw InvalidArgument(
        "--robot, --package-path, --srdf, --self-collision, --self-model, --queries-per-scene "
        "and --learn-from-verification go with the motion-bench experiment");
  }
  std::filesystem::create_directories(dir);
  const auto start = std::chrono::steady_clock::now();
  const Progress progress = [start](std::string_view line) {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[" << static_cast<int>(s) << " s] " << line << std::endl;
  };

  // OMPL draws every planner's seeds from one global generator, which takes a seed only before
  // its first use: planning experiments are repeatable in their queries, not in planning times.
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(o.seed));
  const auto setPlanning = [&o](auto& options, std::size_t defaultTrials) {
    options.seed = o.seed;
    options.quick = o.quick;
    options.features = parseFeatureKind(o.features);
    if (o.timeLimit > 0) options.timeLimit = o.timeLimit;
    if (o.resolution > 0) options.resolution = o.resolution;
    if (o.simplifyTime >= 0) options.simplifyTime = o.simplifyTime;
    if constexpr (requires { options.trials; }) {
      options.trials = o.trials ? o.trials : (o.quick ? 1 : defaultTrials);
    }
  };

  Table results;
  std::string report;
  StaticOptions options;
  options.seed = o.seed;
  options.quick = o.quick;
  if (o.name == "static") {
    options.trials = o.trials ? o.trials : (o.quick ? 1 : 10);
    results = runStatic(options, progress);
    report = staticReport(results, options);
  } else if (o.name == "static-beta" || o.name == "static-gamma") {
    options.trials = o.trials ? o.trials : (o.quick ? 1 : 10);
    const std::string parameter = o.name.substr(7);
    results = runStaticSweep(options, parameter, progress);
    report = staticSweepReport(results, parameter, options);
  } else if (o.name == "changing") {
    ChangingOptions changing;
    changing.trials = o.trials ? o.trials : (o.quick ? 1 : 3);
    changing.steps = o.quick ? 3 : 50;
    changing.seed = o.seed;
    changing.quick = o.quick;
    changing.features = parseFeatureKind(o.features);
    changing.gamma = o.gamma;
    changing.beta = o.beta;
    changing.variance = o.variance;
    if (o.quick) changing.cases = {"4dof", "7dof-3boxes"};
    results = runChanging(changing, progress);
    report = changingReport(results, changing);
  } else if (o.name == "sweep") {
    SweepOptions sweep;
    sweep.trials = o.trials ? o.trials : (o.quick ? 1 : 3);
    sweep.seed = o.seed;
    sweep.quick = o.quick;
    sweep.features = parseFeatureKind(o.features);
    if (o.quick) sweep.obstacles = {1, 10};
    results = runObstacleSweep(sweep, progress);
    report = sweepReport(results, sweep);
  } else if (o.name == "cspace") {
    const CspaceOptions cspace{o.trials ? o.trials : (o.quick ? 1u : 3u), o.seed, o.quick};
    const CspaceResults r = runCspace(cspace, progress);
    results = r.summary;
    r.grid.writeCsv(dir / "grid.csv");
    r.support.writeCsv(dir / "support.csv");
    r.cubes.writeCsv(dir / "cubes.csv");
    report = cspaceReport(r, cspace);
  } else if (o.name == "plan") {
    PlanningOptions planning;
    setPlanning(planning, planning.trials);
    if (o.quick) {
      planning.cases = {"4dof", "7dof-3boxes"};
      planning.timeLimit = o.timeLimit > 0 ? o.timeLimit : 3;
    }
    const PlanRows plans = runPlanning(planning, progress);
    results = plans.table();
    report = planningReport(plans, planning);
  } else if (o.name == "shelf") {
    ShelfOptions shelf;
    setPlanning(shelf, shelf.trials);
    if (o.quick && o.timeLimit <= 0) shelf.timeLimit = 3;
    const PlanRows plans = runShelf(shelf, progress);
    results = plans.table();
    report = shelfReport(plans, shelf);
  } else if (o.name == "surgical") {
    SurgicalOptions surgical;
    setPlanning(surgical, 0);
    if (o.trials) surgical.ticks = o.trials;
    const PlanRows plans = runSurgical(surgical, progress);
    results = plans.table();
    report = surgicalReport(plans, surgical);
  } else if (o.name == "motion-bench") {
    if (o.problems.empty()) {
      throw InvalidArgument(
          "motion-bench needs --problems DIR (a folder of sceneNNNN.yaml and "
          "requestNNNN.yaml files)");
    }
    MotionBenchOptions bench;
    setPlanning(bench, 0);
    bench.problems = o.problems;
    bench.robot = o.robot.robot;
    for (const auto& p : o.robot.packagePaths) bench.packagePaths.emplace_back(p);
    bench.srdf = o.robot.srdf;
    bench.selfCollision = o.selfCollision;
    bench.queriesPerScene = o.queriesPerScene;
    bench.selfModel = o.selfModel;
    bench.learnFromVerification = o.learnFromVerification;
    const PlanRows plans = runMotionBench(bench, progress);
    results = plans.table();
    report = motionBenchReport(plans, bench);
  } else {
    throw InvalidArgument("unknown experiment '" + o.name + "'");
  }

  results.writeCsv(dir / "results.csv");
  std::ofstream(dir / "report.md") << report;
  std::cout << '\n' << report << '\n';
  if (o.plot) {
    const std::string error = runPlotScript("plot_experiments.py", {o.name, dir.string()});
    if (!error.empty()) std::cerr << "fastron: warning: no plots drawn: " << error << '\n';
  }
  std::cout << "results in " << dir.string() << "/: results.csv, report.md"
            << (o.plot ? ", " + o.name + ".png" : "") << '\n';
  return 0;
}

}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Run one of the paper's experiments");
  const std::vector<std::string> names{"static",   "static-beta", "static-gamma", "cspace",
                                       "changing", "sweep",       "plan",         "shelf",
                                       "surgical", "motion-bench"};
  cmd->add_option("name", o->name,
                  "static, static-beta, static-gamma, cspace, changing, sweep, plan, shelf, "
                  "surgical, motion-bench")
      ->required()
      ->check(CLI::IsMember(names));
  cmd->add_option("--trials", o->trials,
                  "trials (random environments, planning queries; surgical: ticks); default: the "
                  "experiment's own");
  cmd->add_option("--problems", o->problems,
                  "motion-bench: folder of MoveIt sceneNNNN.yaml / requestNNNN.yaml pairs");
  o->robot.robot = "panda";
  cmd->add_option("--robot", o->robot.robot,
                  "motion-bench: a shipped robot (e.g. panda-mesh) or a URDF file")
      ->capture_default_str();
  cmd->add_option("--package-path", o->robot.packagePaths,
                  "motion-bench: folder searched for the robot's package:// meshes (repeatable)");
  cmd->add_option("--srdf", o->robot.srdf,
                  "motion-bench: MoveIt SRDF whose disable_collisions pairs are skipped");
  cmd->add_option("--queries-per-scene", o->queriesPerScene,
                  "motion-bench: the request plus K-1 random free start/goal pairs per scene, on "
                  "one model")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--learn-from-verification", o->learnFromVerification,
                "motion-bench: between a scene's queries, the model learns the exact answers of "
                "the last plan's verification and repair that it got wrong");
  cmd->add_flag("--self-model", o->selfModel,
                "motion-bench with --self-collision: also plan on a self-collision model learned "
                "once for the robot beside each scene's obstacle model (method 'Fastron split')");
  cmd->add_flag("--self-collision", o->selfCollision,
                "motion-bench: FCL also checks the robot against itself (SRDF pairs skipped)");
  cmd->add_option("--time-limit", o->timeLimit, "planning experiments: seconds per query")
      ->check(numberAbove(0));
  cmd->add_option("--resolution", o->resolution,
                  "planning experiments: joint-space step of edge checks")
      ->check(numberAbove(0));
  cmd->add_option("--simplify-time", o->simplifyTime,
                  "planning experiments: seconds of OMPL path simplification per plan, every "
                  "checker alike (default 0.1; 0: off, the paper's setting)")
      ->check(numberAbove(0, true));
  cmd->add_option("--seed", o->seed, "seed of every random choice")->capture_default_str();
  addFeatureKindOption(*cmd, o->features);  // changing, sweep and the planning experiments
  cmd->add_option("--gamma", o->gamma, "changing: kernel width of the models on --features")
      ->check(numberAbove(0));
  cmd->add_option("--beta", o->beta, "changing: conditional bias of the models on --features")
      ->check(numberAbove(1, true));
  cmd->add_option("--al-variance", o->variance,
                  "changing: active-learning spread sigma^2 in scaled joint space")
      ->check(numberAbove(0));
  cmd->add_option("--out", o->out, "output folder (default: fastron-results/NAME)");
  cmd->add_flag("--quick", o->quick, "small sizes, for a fast check");
  cmd->add_flag("!--no-plot", o->plot, "skip the PNG plots");
  cmd->callback([o, &exitCode] { exitCode = runBench(*o); });
}

}  // namespace fastron::cli
