#include "fastron/experiments/registry.h"

#include "fastron/core/error.h"
#include "fastron/experiments/changing_experiment.h"
#include "fastron/experiments/cspace_experiment.h"
#include "fastron/experiments/motion_bench_experiment.h"
#include "fastron/experiments/planning_experiment.h"
#include "fastron/experiments/sensed_experiment.h"
#include "fastron/experiments/shelf_experiment.h"
#include "fastron/experiments/static_experiment.h"
#include "fastron/experiments/surgical_experiment.h"
#include "fastron/experiments/trajectory_experiment.h"

namespace fastron::experiments {
namespace {

/// The given trials, or the experiment's: one in quick mode.
std::size_t trialsOr(const ExperimentSettings& s, std::size_t full) {
  return s.trials != 0 ? s.trials : (s.quick ? 1 : full);
}

/// The settings every experiment takes: seed, quick, and the features where it has them.
template <class Options>
void applyCommon(const ExperimentSettings& s, Options& options) {
  options.seed = s.seed;
  options.quick = s.quick;
  if constexpr (requires { options.features; }) options.features = s.features;
}

/// The settings every planning experiment shares.
template <class Options>
void applyPlanning(const ExperimentSettings& s, Options& options) {
  applyCommon(s, options);
  if (s.timeLimit > 0) options.timeLimit = s.timeLimit;
  if (s.resolution > 0) options.resolution = s.resolution;
  if (s.modelResolution > 0) options.modelResolution = s.modelResolution;
  if (s.simplifyTime >= 0) options.simplifyTime = s.simplifyTime;
  if (s.simplification) options.simplification = *s.simplification;
  if constexpr (requires { options.gradientRepair; }) options.gradientRepair = s.gradientRepair;
}

const std::vector<std::string> kPlanningSettings{
    "features", "time-limit", "resolution", "model-resolution", "simplify-time", "simplification"};

std::vector<std::string> planningAnd(std::vector<std::string> more) {
  more.insert(more.begin(), kPlanningSettings.begin(), kPlanningSettings.end());
  return more;
}

/// The output of an experiment whose results are one table, which its report reads.
template <class Report>
ExperimentOutput reported(Table results, const Report& report) {
  std::string text = report(results);
  return {std::move(results), {}, std::move(text)};
}

StaticOptions staticOptions(const ExperimentSettings& s) {
  StaticOptions o;
  applyCommon(s, o);
  o.trials = trialsOr(s, 10);
  return o;
}

ExperimentOutput runStaticSweepOf(const std::string& parameter, const ExperimentSettings& s,
                                  const Progress& progress) {
  const StaticOptions o = staticOptions(s);
  return reported(runStaticSweep(o, parameter, progress),
                  [&](const Table& t) { return staticSweepReport(t, parameter, o); });
}

/// The experiments of Sec. IV-A: static worlds, their sweeps, the learned C-space.
void addStaticExperiments(std::vector<Experiment>& all) {
  all.push_back({"static",
                 "Fastron against ISVM, SSVM and LIBSVM in static 2- and 4-DOF worlds",
                 {},
                 [](const ExperimentSettings& s, const Progress& progress) {
                   const StaticOptions o = staticOptions(s);
                   return reported(runStatic(o, progress),
                                   [&](const Table& t) { return staticReport(t, o); });
                 }});
  all.push_back({"static-beta",
                 "Fastron's accuracy and support set over its conditional bias",
                 {},
                 [](const ExperimentSettings& s, const Progress& progress) {
                   return runStaticSweepOf("beta", s, progress);
                 }});
  all.push_back({"static-gamma",
                 "Fastron's accuracy and support set over its kernel width",
                 {},
                 [](const ExperimentSettings& s, const Progress& progress) {
                   return runStaticSweepOf("gamma", s, progress);
                 }});
  all.push_back({"cspace",
                 "The learned C-space of a 2-DOF arm beside the true one (Fig. 3)",
                 {},
                 [](const ExperimentSettings& s, const Progress& progress) {
                   const CspaceOptions o{trialsOr(s, 3), s.seed, s.quick};
                   CspaceResults r = runCspace(o, progress);
                   ExperimentOutput out;
                   out.report = cspaceReport(r, o);
                   out.results = std::move(r.summary);
                   out.tables = {{"grid.csv", std::move(r.grid)},
                                 {"support.csv", std::move(r.support)},
                                 {"cubes.csv", std::move(r.cubes)}};
                   return out;
                 }});
}

/// The experiments of Sec. IV-B: moving boxes and the query time over obstacles.
void addChangingExperiments(std::vector<Experiment>& all) {
  all.push_back({"changing",
                 "Baxter among moving boxes: accuracy and update time per step",
                 {"features", "gamma", "beta", "al-variance", "active-samples", "warm-start",
                  "prune-samples", "merge-radius", "kernel-block", "kernel-whole-share"},
                 [](const ExperimentSettings& s, const Progress& progress) {
                   ChangingOptions o;
                   o.trials = trialsOr(s, 3);
                   o.steps = s.quick ? 3 : 50;
                   applyCommon(s, o);
                   o.gamma = s.gamma;
                   o.beta = s.beta;
                   o.variance = s.variance;
                   o.activeSamples = s.activeSamples;
                   o.warmStart = s.warmStart;
                   o.pruneSamples = s.pruneSamples;
                   o.mergeRadius = s.mergeRadius;
                   o.kernelBlock = s.kernelBlock;
                   o.wholeShare = s.wholeShare;
                   if (s.quick) o.cases = {"4dof", "7dof-3boxes"};
                   return reported(runChanging(o, progress),
                                   [&](const Table& t) { return changingReport(t, o); });
                 }});
  all.push_back({"sweep",
                 "Query time over the number of obstacles (Fig. 5)",
                 {"features"},
                 [](const ExperimentSettings& s, const Progress& progress) {
                   SweepOptions o;
                   o.trials = trialsOr(s, 3);
                   applyCommon(s, o);
                   if (s.quick) o.obstacles = {1, 10};
                   return reported(runObstacleSweep(o, progress),
                                   [&](const Table& t) { return sweepReport(t, o); });
                 }});
}

/// The planning experiments of Secs. IV-C and V, and MotionBenchMaker problems.
void addPlanningExperiments(std::vector<Experiment>& all) {
  all.push_back({"plan", "Baxter planning with each OMPL planner on each checker (Table IV)",
                 kPlanningSettings, [](const ExperimentSettings& s, const Progress& progress) {
                   PlanningOptions o;
                   applyPlanning(s, o);
                   o.trials = trialsOr(s, o.trials);
                   if (s.quick) {
                     o.cases = {"4dof", "7dof-3boxes"};
                     if (s.timeLimit <= 0) o.timeLimit = 3;
                   }
                   const PlanRows plans = runPlanning(o, progress);
                   return ExperimentOutput{plans.table(), {}, planningReport(plans, o)};
                 }});
  all.push_back({"shelf", "UR3 from the lower to the higher shelf with RRT", kPlanningSettings,
                 [](const ExperimentSettings& s, const Progress& progress) {
                   ShelfOptions o;
                   applyPlanning(s, o);
                   o.trials = trialsOr(s, o.trials);
                   if (s.quick && s.timeLimit <= 0) o.timeLimit = 3;
                   const PlanRows plans = runShelf(o, progress);
                   return ExperimentOutput{plans.table(), {}, shelfReport(plans, o)};
                 }});
  all.push_back({"surgical", "A surgical arm replanning among two moving arms every tick",
                 kPlanningSettings, [](const ExperimentSettings& s, const Progress& progress) {
                   SurgicalOptions o;
                   applyPlanning(s, o);
                   if (s.trials != 0) o.ticks = s.trials;
                   const PlanRows plans = runSurgical(o, progress);
                   return ExperimentOutput{plans.table(), {}, surgicalReport(plans, o)};
                 }});
  all.push_back({"sensed",
                 "Baxter among moving boxes seen through a depth camera: cloud ingest, model "
                 "updates per second, plans verified on the cloud",
                 planningAnd({"gamma", "beta", "active-samples"}),
                 [](const ExperimentSettings& s, const Progress& progress) {
                   SensedOptions o;
                   applyPlanning(s, o);
                   o.gamma = s.gamma;
                   o.beta = s.beta;
                   o.activeSamples = s.activeSamples;
                   o.trials = trialsOr(s, 3);
                   SensedResults r = runSensed(o, progress);
                   std::string report = sensedReport(r, o);
                   return ExperimentOutput{std::move(r.frames),
                                           {{"plans.csv", r.plans.table()},
                                            {"scene.csv", std::move(r.scene)},
                                            {"path.csv", std::move(r.path)}},
                                           std::move(report)};
                 }});
  all.push_back({"optimize",
                 "Baxter among three moving boxes: CHOMP-style optimisation on the model's "
                 "collision cost from a colliding straight line, against RRT-Connect on FCL and on "
                 "the model",
                 planningAnd({"gradient-repair"}),
                 [](const ExperimentSettings& s, const Progress& progress) {
                   TrajectoryExperimentOptions o;
                   applyPlanning(s, o);
                   o.trials = s.trials != 0 ? s.trials : (s.quick ? 3 : 10);
                   TrajectoryResults r = runTrajectories(o, progress);
                   std::string report = trajectoryReport(r, o);
                   return ExperimentOutput{
                       std::move(r.results), {{"scores.csv", std::move(r.scores)}}, report};
                 }});
  all.push_back({"motion-bench", "MotionBenchMaker problems (MoveIt scenes and requests)",
                 planningAnd({"problems", "robot", "package-path", "srdf", "range", "range-stage",
                              "self-collision", "dense-checks", "self-model", "queries-per-scene",
                              "learn-from-verification", "samples", "updates", "gamma", "beta",
                              "gradient-repair"}),
                 [](const ExperimentSettings& s, const Progress& progress) {
                   if (s.problems.empty()) {
                     throw InvalidArgument(
                         "motion-bench needs --problems DIR (a folder of sceneNNNN.yaml and "
                         "requestNNNN.yaml files)");
                   }
                   MotionBenchOptions o;
                   applyPlanning(s, o);
                   o.problems = s.problems;
                   o.robot = s.robot;
                   o.packagePaths = s.packagePaths;
                   o.srdf = s.srdf;
                   o.resultsFile = s.resultsFile;
                   o.range = s.range;
                   o.rangeStage = s.rangeStage;
                   o.selfCollision = s.selfCollision;
                   o.denseChecks = s.denseChecks;
                   o.selfPairTables = s.selfPairTables;
                   o.queriesPerScene = s.queriesPerScene;
                   o.selfModel = s.selfModel;
                   o.learnFromVerification = s.learnFromVerification;
                   o.trainingPoints = s.samples;
                   o.updates = s.updates;
                   if (s.gamma > 0) o.gamma = s.gamma;
                   if (s.beta > 0) o.beta = s.beta;
                   const PlanRows plans = runMotionBench(o, progress);
                   return ExperimentOutput{plans.table(), {}, motionBenchReport(plans, o)};
                 }});
}

std::vector<Experiment> makeRegistry() {
  std::vector<Experiment> all;
  addStaticExperiments(all);
  addChangingExperiments(all);
  addPlanningExperiments(all);
  return all;
}

}  // namespace

const std::vector<Experiment>& experimentRegistry() {
  static const std::vector<Experiment> registry = makeRegistry();
  return registry;
}

const Experiment& findExperiment(std::string_view name) {
  std::string names;
  for (const Experiment& e : experimentRegistry()) {
    if (e.name == name) return e;
    names += (names.empty() ? "" : ", ") + e.name;
  }
  throw InvalidArgument("unknown experiment '" + std::string(name) + "' (" + names + ")");
}

}  // namespace fastron::experiments
