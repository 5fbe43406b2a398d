// fastron bench NAME: one of the paper's experiments; raw results as CSV, the paper's tables as
// Markdown with the paper's values beside ours, and the paper's figures as PNG.

#include <ompl/util/RandomNumbers.h>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/error.h"
#include "fastron/experiments/registry.h"
#include "plotting.h"
#include "report_format.h"
#include "robot_options.h"

namespace fastron::cli {

using namespace experiments;  // the command runs the experiments layer
namespace {

struct BenchOptions {
  std::string name, out, problems, features = "fk";
  ExperimentSettings settings;
  RobotOptions robot;  // motion-bench only (default: panda)
  bool plot = true;
};

/// The options that only some experiments read, by name; a given one the experiment does not
/// read is refused, naming the experiments that do.
void refuseSettingsNotRead(const CLI::App& cmd, const Experiment& experiment) {
  for (const CLI::Option* option : cmd.get_options()) {
    const std::string name = option->get_lnames().empty() ? "" : option->get_lnames().front();
    if (name.empty() || option->count() == 0) continue;
    bool readBySome = false, readByThis = false;
    std::string readers;
    for (const Experiment& e : experimentRegistry()) {
      if (std::find(e.settings.begin(), e.settings.end(), name) == e.settings.end()) continue;
      readBySome = true;
      readByThis = readByThis || &e == &experiment;
      readers += (readers.empty() ? "" : ", ") + e.name;
    }
    if (readBySome && !readByThis) {
      throw InvalidArgument("--" + name + " does not apply to " + experiment.name +
                            ": it goes with " + readers);
    }
  }
}

int runBench(const CLI::App& cmd, BenchOptions o) {
  const Experiment& experiment = findExperiment(o.name);
  refuseSettingsNotRead(cmd, experiment);
  ExperimentSettings& s = o.settings;
  s.features = parseFeatureKind(o.features);
  s.problems = o.problems;
  s.robot = o.robot.robot;
  for (const auto& p : o.robot.packagePaths) s.packagePaths.emplace_back(p);
  s.srdf = o.robot.srdf;

  const std::filesystem::path dir = o.out.empty()
                                        ? std::filesystem::path("fastron-results") / o.name
                                        : std::filesystem::path(o.out);
  std::filesystem::create_directories(dir);
  s.resultsFile = dir / "results.csv";  // rows so far, for experiments that write them as they go
  // OMPL draws every planner's seeds from one global generator, which takes a seed only before
  // its first use: planning experiments are repeatable in their queries, not in planning times.
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(s.seed));
  const ExperimentOutput output = experiment.run(s, progressPrinter());

  output.results.writeCsv(dir / "results.csv");
  for (const auto& [file, table] : output.tables) table.writeCsv(dir / file);
  std::ofstream(dir / "report.md") << output.report;
  std::cout << '\n' << output.report << '\n';
  if (o.plot) {
    const std::string error = runPlotScript("plot_experiments.py", {o.name, dir.string()});
    if (!error.empty()) std::cerr << "fastron: warning: no plots drawn: " << error << '\n';
  }
  std::cout << "results in " << dir.string() << "/: results.csv, report.md"
            << (o.plot ? ", " + o.name + ".png" : "") << '\n';
  return 0;
}

/// The options of motion-bench: its problems, robot, models and checks.
void addMotionBenchOptions(CLI::App& cmd, BenchOptions& o) {
  cmd.add_option("--problems", o.problems,
                 "motion-bench: folder of MoveIt sceneNNNN.yaml / requestNNNN.yaml pairs");
  o.robot.robot = "panda";
  cmd.add_option("--robot", o.robot.robot,
                 "motion-bench: a shipped robot (e.g. panda-mesh) or a URDF file")
      ->capture_default_str();
  cmd.add_option("--package-path", o.robot.packagePaths,
                 "motion-bench: folder searched for the robot's package:// meshes (repeatable)");
  cmd.add_option("--srdf", o.robot.srdf,
                 "motion-bench: MoveIt SRDF whose disable_collisions pairs are skipped");
  cmd.add_option("--queries-per-scene", o.settings.queriesPerScene,
                 "motion-bench: the request plus K-1 random free start/goal pairs per scene, on "
                 "one model")
      ->check(numberAbove(0))
      ->capture_default_str();
  cmd.add_option("--samples", o.settings.samples,
                 "motion-bench: uniform samples of each scene's models before active learning "
                 "(default 1000)")
      ->check(numberAbove(0));
  cmd.add_option(
      "--updates", o.settings.updates,
      "motion-bench: active-learning updates of each scene's models after those "
      "samples (default 0), and of --self-model's (default 3, as plan --self-model auto)");
  cmd.add_flag("--learn-from-verification", o.settings.learnFromVerification,
               "motion-bench: between a scene's queries, the paper's model learns the exact "
               "answers of the last plan's verification and repair that it got wrong");
  cmd.add_flag("--gradient-repair", o.settings.gradientRepair,
               "motion-bench, optimize: before replanning a colliding stretch, the default "
               "method's model learns its exact answers and pushes it out along the gradient of "
               "its collision cost");
  cmd.add_flag("--self-model", o.settings.selfModel,
               "motion-bench with --self-collision: also plan on a self-collision model learned "
               "once for the robot beside each scene's obstacle model (method 'Fastron split')");
  cmd.add_flag("--self-collision", o.settings.selfCollision,
               "motion-bench: FCL also checks the robot against itself (SRDF pairs skipped); "
               "the default method 'Fastron' then models each scene's obstacles alone and "
               "leaves self-collisions to verification");
  cmd.add_flag("!--no-self-pair-tables", o.settings.selfPairTables,
               "motion-bench: FCL checks self pairs of meshes without the robot's self-pair tables "
               "(built once per robot and kept in the cache; for comparison)");
  cmd.add_flag("--dense-checks", o.settings.denseChecks,
               "motion-bench: FCL checks every state of a motion instead of skipping what "
               "clearance bounds prove free (the same answers, slower; for comparison)");
  cmd.add_option("--range", o.settings.range,
                 "motion-bench: longest tree edge of every method's planner to begin with, "
                 "joint units (default: OMPL's, a fifth of the diagonal of the joint limits); "
                 "RRT-Connect halves it after --range-stage iterations without a path")
      ->check(numberAbove(0));
  cmd.add_option("--range-stage", o.settings.rangeStage,
                 "motion-bench: RRT-Connect's iterations without a path before its range is "
                 "halved, down to an eighth, then the first range again, each round of ranges "
                 "twice as long (default 100; 0: the range stays)");
}

/// The options of every planning experiment: time, resolutions, simplification.
void addPlanningOptions(CLI::App& cmd, BenchOptions& o) {
  cmd.add_option("--time-limit", o.settings.timeLimit, "planning experiments: seconds per query")
      ->check(numberAbove(0));
  cmd.add_option("--resolution", o.settings.resolution,
                 "planning experiments: joint-space step of edge checks")
      ->check(numberAbove(0));
  cmd.add_option("--model-resolution", o.settings.modelResolution,
                 "planning experiments: joint-space step of edge checks on a Fastron model or "
                 "its hybrid (default: 3 times --resolution; every such path is verified with "
                 "FCL at --resolution)")
      ->check(numberAbove(0));
  cmd.add_option("--simplify-time", o.settings.simplifyTime,
                 "planning experiments: seconds of OMPL path simplification per plan, every "
                 "checker alike (default 0.1; 0: off, the paper's setting)")
      ->check(numberAbove(0, true));
  addSimplificationOption(
      cmd, [&o](PathSimplification s) { o.settings.simplification = s; }, "planning experiments: ");
}

/// The options of the models of changing (and of motion-bench's scene models): kernel, bias, active
/// learning, support reduction.
void addModelOptions(CLI::App& cmd, BenchOptions& o) {
  cmd.add_option("--gamma", o.settings.gamma,
                 "changing: kernel width of the models on --features; motion-bench: of each "
                 "scene's models")
      ->check(numberAbove(0));
  cmd.add_option("--beta", o.settings.beta,
                 "changing: conditional bias of the models on --features; motion-bench: of each "
                 "scene's models")
      ->check(numberAbove(1, true));
  cmd.add_option("--kernel-block", o.settings.kernelBlock,
                 "changing: features per kernel point term of the models on --features (0: "
                 "one term over all features; 3: one per control point, the default for fk)");
  cmd.add_option("--kernel-whole-share", o.settings.wholeShare,
                 "changing: the whole feature vector's share of the kernel beside its point "
                 "terms, in [0, 1]")
      ->check(CLI::Range(0.0, 1.0));
  cmd.add_option("--al-variance", o.settings.variance,
                 "changing: active-learning spread sigma^2 in scaled joint space")
      ->check(numberAbove(0));
  cmd.add_option("--active-samples", o.settings.activeSamples,
                 "changing: A_max, the active-learning configurations of each update of the "
                 "models on --features (default 2500 for fk, 500 for joints, the paper's)")
      ->check(numberAbove(0));
  cmd.add_flag("--warm-start", o.settings.warmStart,
               "changing: the models on --features update from their last weights with samples "
               "around every support point, as in the paper (default for fk: from zero weights, "
               "at most a fifth of the samples around support points)");
  cmd.add_option("--prune-samples", o.settings.pruneSamples,
                 "changing: also a row 'Fastron (FCL, pruned)': each model without the support "
                 "points that no answer on this many fresh uniform configurations needs");
  cmd.add_option("--merge-radius", o.settings.mergeRadius,
                 "changing: also a row 'Fastron (FCL, merged)': each model with its support points "
                 "of one sign closer than this in feature space merged (D-Fastron)")
      ->check(numberAbove(0));
}

}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Run one of the paper's experiments");
  std::vector<std::string> names;
  std::string described;
  for (const Experiment& e : experimentRegistry()) {
    names.push_back(e.name);
    described += (described.empty() ? "" : "; ") + e.name + ": " + e.description;
  }
  cmd->add_option("name", o->name, described)->required()->check(CLI::IsMember(names));
  cmd->add_option("--trials", o->settings.trials,
                  "trials (random environments, planning queries; surgical: ticks); default: the "
                  "experiment's own");
  addMotionBenchOptions(*cmd, *o);
  addPlanningOptions(*cmd, *o);
  cmd->add_option("--seed", o->settings.seed, "seed of every random choice")->capture_default_str();
  addFeatureKindOption(*cmd, o->features);  // changing, sweep and the planning experiments
  addModelOptions(*cmd, *o);
  cmd->add_option("--out", o->out, "output folder (default: fastron-results/NAME)");
  cmd->add_flag("--quick", o->settings.quick, "small sizes, for a fast check");
  cmd->add_flag("!--no-plot", o->plot, "skip the PNG plots");
  cmd->callback([cmd, o, &exitCode] { exitCode = runBench(*cmd, *o); });
}

}  // namespace fastron::cli
