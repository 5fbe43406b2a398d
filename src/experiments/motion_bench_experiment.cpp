#include "fastron/experiments/motion_bench_experiment.h"
#include "fastron/pipeline/presets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

#include "fastron/core/active_learning.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model_checker.h"
#include "fastron/experiments/problem_families.h"
#include "fastron/experiments/report_text.h"
#include "fastron/experiments/statistics.h"
#include "fastron/experiments/timing.h"
#include "fastron/geometry/moveit_request.h"
#include "fastron/geometry/point_kinematics.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/geometry/urdf.h"
#include "fastron/pipeline/scene_model.h"
#include "fastron/pipeline/self_model.h"
#include "fastron/pipeline/self_pair_tables.h"
#include "fastron/planning/motion.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/labelling.h"
#include "plan_rows.h"

namespace fastron::experiments {

namespace {

struct Problem {
  std::string family, id;
  std::filesystem::path scene, request;
};

/// The sceneNNNN.yaml files of `folder` that have a requestNNNN.yaml beside them, in order, as
/// problems of `family`.
std::vector<Problem> pairsIn(const std::filesystem::path& folder, const std::string& family) {
  std::vector<Problem> problems;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("scene") || entry.path().extension() != ".yaml") continue;
    const std::string id = name.substr(5, name.size() - 10);
    const auto request = folder / ("request" + id + ".yaml");
    if (std::filesystem::exists(request)) problems.push_back({family, id, entry.path(), request});
  }
  std::sort(problems.begin(), problems.end(),
            [](const Problem& a, const Problem& b) { return a.id < b.id; });
  return problems;
}

/// The problems of `folder`: its own scene/request pairs (one family, named after the folder), or
/// else those of each sub-folder (a family each, in name order).
std::vector<Problem> problemsIn(const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder)) {
    throw FileError(folder.string() + ": not a folder of sceneNNNN.yaml / requestNNNN.yaml files");
  }
  const std::filesystem::path absolute = std::filesystem::absolute(folder).lexically_normal();
  const std::string name =
      (absolute.has_filename() ? absolute : absolute.parent_path()).filename().string();
  std::vector<Problem> problems = pairsIn(folder, name);
  if (!problems.empty()) return problems;
  std::vector<std::filesystem::path> families;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.is_directory()) families.push_back(entry.path());
  }
  std::sort(families.begin(), families.end());
  for (const auto& family : families) {
    const std::vector<Problem> more = pairsIn(family, family.filename().string());
    problems.insert(problems.end(), more.begin(), more.end());
  }
  if (problems.empty()) {
    throw FileError(folder.string() +
                    ": no sceneNNNN.yaml with a matching requestNNNN.yaml, in it or in a folder "
                    "in it");
  }
  return problems;
}

/// When the goal touches obstacles with the hand only (a grasp), allows those hand-object pairs
/// in the scene and returns a note naming them; returns a note saying why otherwise.
std::string allowGrasp(const Robot& robot, Scene& scene, const Eigen::VectorXd& goal) {
  const auto span = std::span<const double>(goal.data(), static_cast<std::size_t>(goal.size()));
  std::string note;
  for (int round = 0; round < 4; ++round) {
    const auto contact = makeSceneChecker("fcl", robot, scene)->firstContact(span);
    if (!contact) return note;
    const bool hand = contact->robotLink.find("hand") != std::string::npos ||
                      contact->robotLink.find("finger") != std::string::npos;
    if (contact->selfCollision || !hand) {
      return note + (note.empty() ? "" : "; ") + "goal collides: " + describe(*contact);
    }
    for (const Link& link : robot.links()) {
      if (link.name.find("hand") != std::string::npos ||
          link.name.find("finger") != std::string::npos)
        scene.allowedCollisions.allow(link.name, contact->other);
    }
    note += (note.empty() ? "grasp: hand may touch " : ", ") + contact->other;
  }
  return note;
}

/// Fresh uniform configurations per scene on which the trained models are scored.
std::size_t testPoints(const MotionBenchOptions& o) {
  return o.quick ? 300 : 1000;
}

constexpr double kNearWalls = 0.02;  // metres: "near a wall" in the report

struct AlongFclPath {
  double nearWalls = std::numeric_limits<double>::quiet_NaN();
  double calledColliding = std::numeric_limits<double>::quiet_NaN();
};

/// Where the model stands along FCL's own path of a request: of the states a check of that path
/// at `resolution` looks at (the audit's check: free), the share within kNearWalls of an obstacle
/// and the share the model calls colliding. A model is wrong near walls in every family, and a
/// plan on it fails where every way to the goal passes near them (docs/planning.md, "Families
/// beyond the samples"). NaN when FCL found no path.
AlongFclPath alongFclPath(const VerifiedPlan& fclPlan, const Model& model,
                          const SceneChecker& audit, double resolution) {
  if (!fclPlan.solved()) return {};
  const Configurations states = statesAlongPath(fclPlan.path, resolution);
  const std::vector<double> clearance = clearances(audit, states);
  const Eigen::VectorXd scores = model.scoreBatch(states);
  const auto n = static_cast<double>(states.rows());
  return {static_cast<double>(std::count_if(clearance.begin(), clearance.end(),
                                            [](double d) { return d < kNearWalls; })) /
              n,
          static_cast<double>((scores.array() > 0).count()) / n};
}

/// trainStatic; the seconds it took.
double train(ProxyCollisionDetector& proxy, std::size_t samples, std::size_t updates) {
  return inSeconds(trainStatic(proxy, samples, updates).total);
}

std::size_t trainingSamples(const MotionBenchOptions& o) {
  return o.trainingPoints.value_or(pipeline::SceneModelOptions{}.samples);
}

std::size_t trainingUpdates(const MotionBenchOptions& o) {
  return o.updates.value_or(pipeline::SceneModelOptions{}.updates);
}

/// A scene model's parameters with the options' kernel width and conditional bias, if given.
ProxyParams withKernelOptions(ProxyParams params, const MotionBenchOptions& o) {
  if (o.gamma) params.train.kernel.gamma = *o.gamma;
  if (o.beta) params.train.beta = *o.beta;
  return params;
}

/// "Median end-to-end time of FCL / of each method, training included (...): RRTConnect: NAME
/// N.Nx ...": per solved plan, its total plus its scene's training shared by `queries` queries
/// (with one, the requests alone).
std::string endToEndSpeedups(const PlanRows& r, const RowFilter& where, std::size_t queries) {
  const RowFilter kept = [&](const PlanRow& row) {
    return (!where || where(row)) && (queries > 1 || row.queryValue("query") == "0");
  };
  return ratioLine(
      r, kept, {"RRTConnect"},
      "Median end-to-end time of FCL / of each method, training included (" +
          (queries == 1 ? std::string("one query") : std::to_string(queries) + " queries") +
          " per scene)",
      [&](const PlanRow& row) {
        const double training = row.method == "FCL" ? 0 : row.figure("train_s");
        return row.outcome.totalSeconds + training / static_cast<double>(queries);
      },
      true);
}

/// What a problem's robot shares with the problems before it: models and features depend on the
/// robot's actuated joints and held positions (kinematicsChecksum), which each request may set.
struct RobotModels {
  std::optional<std::uint64_t> checksum;  ///< none before the first problem's robot
  FeatureMap features;
  /// The default method's: its first scene's model chooses among them on held-out labels
  /// (pipeline::trainSceneModel), and the robot's other scenes train the one chosen (the choice
  /// depends on the robot more than on the scene:
  /// docs/log/2026-11-29-control-points-of-scene-models.md).
  std::vector<pipeline::FeatureCandidate> candidates;
  /// With MotionBenchOptions::selfModel: the robot's self-collision model as a checker of its
  /// configurations (pipeline::selfModelChecker).
  std::shared_ptr<const CollisionChecker> selfModel;
  double selfTrainSeconds = 0;
  /// The robot's self-pair tables (MotionBenchOptions::selfPairTables), given to every FCL
  /// checker of its scenes but the audit's.
  std::shared_ptr<const std::vector<SelfPairTable>> selfTables;
};

/// The robot's self-collision model, learned once per robot and kept in the cache
/// (pipeline::selfCollisionModel): self-collision does not depend on the scene.
void learnSelfCollisions(const Robot& robot, const MotionBenchOptions& o, const Progress& progress,
                         RobotModels& models) {
  if (progress) progress("motion-bench: the robot's self-collision model");
  const pipeline::SelfModel self = pipeline::selfCollisionModel(
      robot, {.samples = o.quick ? 2000 : o.selfTrainingPoints,
              .updates = o.updates.value_or(pipeline::SelfModelOptions{}.updates),
              .seed = o.seed,
              .cacheDirectory = o.selfModelCache});
  if (progress)
    progress("motion-bench: self-collision model " +
             std::string(self.fromCache ? "read from " : "trained and kept in ") +
             self.file.string());
  models.selfTrainSeconds = self.trainSeconds;
  models.selfModel = pipeline::selfModelChecker(robot, self.model);
}

/// The robot's self-pair tables, built once per robot and kept in the cache
/// (pipeline::selfPairTables); the report says where they came from.
void tabulateSelfPairs(const Robot& robot, const MotionBenchOptions& o, const Progress& progress,
                       RobotModels& models, PlanRows& results) {
  const pipeline::SelfPairTables tables =
      pipeline::selfPairTables(robot, {.cacheDirectory = o.selfModelCache});
  models.selfTables = tables.tables;
  if (!tables.tables) return;  // no self pair of meshes
  const std::string note = "Self-pair tables of " + robot.name() + ": " +
                           selfPairTablesText(tables) +
                           " (once per robot, not counted in any method's time); every FCL "
                           "checker reads them but the audit's.";
  results.notes.push_back(note);
  if (!tables.warning.empty()) results.warnings.push_back(tables.warning);
  if (progress) progress("motion-bench: " + note);
}

/// `rows` as results.csv so far, written whole to a new file then moved over `path`: an
/// interrupted run leaves the problems it finished.
void writeRowsSoFar(const PlanRows& rows, const std::filesystem::path& path) {
  if (path.empty()) return;
  std::filesystem::path partial = path;
  partial += ".part";
  rows.table().writeCsv(partial);
  std::filesystem::rename(partial, path);
}

/// What the queries of one problem share: its robot and ends, the exact checkers, the scene's
/// models (the paper's recipe, the default method's, the split source) and their scores.
struct ProblemRun {
  explicit ProblemRun(Robot r) : robot(std::move(r)) {}
  Robot robot;
  PlanRequest request;
  Eigen::VectorXd start, goal;
  std::string note;                                ///< a grasp allowed, or empty
  std::shared_ptr<const SceneChecker> fcl, audit;  ///< the planners' and the final paths' judge
  std::unique_ptr<ProxyCollisionDetector> paper;   ///< the paper's model of everything FCL checks
  CalibratedModel calibrated;
  double paperTrain = 0, paperSupport = 0;
  ConfusionCounts paperQuality;
  pipeline::SceneModel obstacles;  ///< the default method's model
  double obstaclesSupport = 0;     ///< its |S| as trained (the split source's)
  std::string obstacleFeatures;    ///< the name of its features' candidate
  Configurations test;             ///< fresh uniform configurations the models are scored on
  Labels truth, obstacleTruth;     ///< of `test`, by the audit and by the default model's oracle
  std::shared_ptr<const CollisionChecker> split;  ///< with a self-collision model
  ConfusionCounts splitQuality;
};

/// Reads problem `p`, finds its robot (the request's group; RobotModels follow a new robot) and
/// trains the scene's models.
ProblemRun prepareProblem(const Problem& problem, std::size_t p,
                          const RobotDescription& description, const MotionBenchOptions& o,
                          const Progress& progress, RobotModels& models, PlanRows& results) {
  Scene scene = loadScene(problem.scene);
  PlanRequest request = loadMoveItRequest(problem.request);
  RequestRobot forRequest = robotForRequest(description.robot, description.srdf.groups, scene,
                                            request, problem.request.string());
  if (!forRequest.warning.empty() && std::find(results.warnings.begin(), results.warnings.end(),
                                               forRequest.warning) == results.warnings.end())
    results.warnings.push_back(forRequest.warning);
  ProblemRun run(std::move(forRequest.robot));
  run.request = std::move(request);
  const Robot& robot = run.robot;
  if (const std::uint64_t checksum = kinematicsChecksum(robot); checksum != models.checksum) {
    models = {checksum, robotFeatures(robot, o.features),
              pipeline::automaticFeatureCandidates(robot, o.features), nullptr, 0};
    if (o.selfModel) learnSelfCollisions(robot, o, progress, models);
    if (o.selfCollision && !o.denseChecks && o.selfPairTables)
      tabulateSelfPairs(robot, o, progress, models, results);
  }
  const CheckerOptions audited{.selfCollision = o.selfCollision,
                               .proveMotionsFree = !o.denseChecks};
  CheckerOptions checking = audited;
  checking.selfPairTables = models.selfTables;
  const RequestEnds ends = requestEnds(robot, run.request, problem.request.string());
  run.start = ends.start;
  run.goal = ends.goal;
  run.note = allowGrasp(robot, scene, run.goal);
  run.fcl = makeSceneChecker("fcl", robot, scene, checking);
  run.audit = makeSceneChecker("fcl", robot, scene, audited);

  const ProxyParams params =
      withKernelOptions(pipeline::forStaticScene(pipeline::robotProxyParams(
                            o.features, 5, 500, o.seed + p, o.selfCollision)),
                        o);
  run.paper = std::make_unique<ProxyCollisionDetector>(run.fcl, models.features, params);
  run.paperTrain = train(*run.paper, trainingSamples(o), trainingUpdates(o));
  run.calibrated = run.paper->calibratedModel();
  run.paperSupport = static_cast<double>(run.calibrated.model->supportCount());
  // The models' accuracy beside their speed: fresh uniform configurations of this scene,
  // labelled by the audit FCL (self-collision included when it is checked).
  Rng testRng(o.seed * 104729 + p);
  run.test = uniformConfigurations(robot.limits(), testPoints(o), testRng);
  run.truth = labelConfigurations(*run.audit, run.test, 1);
  run.paperQuality = evaluate(*run.calibrated.model, run.test, run.truth);
  // The default method's model (what `fastron plan` trains, pipeline::trainSceneModel): of this
  // scene's obstacles alone (self-collisions, when checked, left to verification and learned
  // from it). With the robot's self-collision model beside it, also the split source.
  run.obstacles = pipeline::trainSceneModel(robot, scene, checking, models.candidates,
                                            {.samples = trainingSamples(o),
                                             .updates = trainingUpdates(o),
                                             .seed = o.seed + p,
                                             .gamma = o.gamma,
                                             .beta = o.beta,
                                             .checker = std::string(kDefaultSceneChecker)});
  run.obstacleFeatures = models.candidates[run.obstacles.chosen].name;
  models.candidates = {models.candidates[run.obstacles.chosen]};
  run.obstaclesSupport = static_cast<double>(run.obstacles.detector->model()->supportCount());
  run.obstacleTruth =  // of `test`, by the model's oracle
      o.selfCollision ? labelConfigurations(*run.obstacles.oracle, run.test, 1) : run.truth;
  if (models.selfModel) {
    run.split = pipeline::splitModel(run.obstacles.detector->model(), models.selfModel);
    const std::vector<std::uint8_t> predicted = run.split->inCollisionBatch(run.test);
    run.splitQuality = confusionOf(run.truth, [&](std::size_t i) { return predicted[i] != 0; });
  }
  return run;
}

/// Every method's plan of query `query` of problem `p` (0: the request; the others join two
/// configurations free under FCL drawn from `rng`), as rows, the default method's first.
std::vector<PlanRow> planQuery(ProblemRun& run, const Problem& problem, std::size_t p,
                               std::size_t query, const MotionBenchOptions& o,
                               const RobotModels& models, Rng& rng) {
  const JointLimits limits = run.robot.limits();
  const PlannerOptions options = plannerOptions(o, PlannerType::RrtConnect);
  const auto freeConfiguration = [&] {
    return sampleFree(
        *run.fcl, [&] { return uniformIn(limits, rng); }, "configuration");
  };
  const Eigen::VectorXd from = query == 0 ? run.start : freeConfiguration();
  Eigen::VectorXd to = query == 0 ? run.goal : freeConfiguration();
  // As `fastron problems` gives its goals: not a turn away on a joint of more than a turn.
  if (query > 0)
    takeTurnsNearestStart(run.robot, std::span<const double>(from.data(), limits.dim()),
                          std::span<double>(to.data(), limits.dim()));
  double learnSeconds = 0;
  if (o.learnFromVerification && query > 0) {  // what the last query's plan taught it
    learnSeconds = std::chrono::duration<double>(run.paper->learnObservations().total).count();
    run.calibrated = run.paper->calibratedModel();
    run.paperSupport = static_cast<double>(run.calibrated.model->supportCount());
    // Each row scores the model it used.
    run.paperQuality = evaluate(*run.calibrated.model, run.test, run.truth);
  }
  const std::vector<std::pair<std::string, std::string>> queryColumns{
      {"family", problem.family},
      {"problem", problem.id},
      {"query", std::to_string(query)},
      {"group", run.request.group.empty() ? "-" : run.request.group},
      {"note", query == 0 ? run.note : ""}};
  const std::size_t turn = p * o.queriesPerScene + query;
  const std::vector<MethodPlan> plans = planWithEachChecker(
      run.calibrated, nullptr, run.fcl, limits, from, to, options, o.seed, turn);
  // Measured on the request only: its distances cost about a second per path on a mesh robot.
  AlongFclPath along;
  if (query == 0) {
    const auto exact = std::find_if(plans.begin(), plans.end(),
                                    [](const MethodPlan& m) { return m.method == "FCL"; });
    if (exact != plans.end()) {
      along = alongFclPath(exact->plan, *run.obstacles.detector->model(), *run.audit, o.resolution);
    }
  }
  std::vector<PlanRow> rows;
  const auto addRow = [&](const MethodPlan& each, double modelSupport,
                          const ConfusionCounts& modelQuality, double trainS, double learnS) {
    rows.push_back({queryColumns,
                    "RRTConnect",
                    each.method,
                    outcomeOf(each, *run.audit, o.resolution),
                    {{"support", modelSupport},
                     {"cover_rule",
                      each.method == kDefaultMethod && run.obstacleFeatures == "cover" ? 1.0 : 0.0},
                     {"accuracy", modelQuality.accuracy()},
                     {"tpr", modelQuality.tpr()},
                     {"train_s", trainS},
                     {"self_train_s", models.selfTrainSeconds},
                     {"learn_s", learnS},
                     {"fcl_path_near_walls", along.nearWalls},
                     {"fcl_path_called_colliding", along.calledColliding}}});
  };
  for (const MethodPlan& each : plans) {
    if (o.learnFromVerification && each.method == "Fastron") {
      run.paper->addObservations(answersMissedBy(*run.calibrated.model, each.plan.exactAnswers));
    }
    MethodPlan named = each;  // the paper's recipe, beside the default method
    if (each.method != "FCL") named.method = each.method + " (paper)";
    addRow(named, run.paperSupport, run.paperQuality, run.paperTrain, learnSeconds);
  }
  const double obstaclesTrain = run.obstacles.trainSeconds;
  if (run.split) {
    seedPlanners(o.seed, turn);
    addRow({"Fastron split",
            pipeline::planOnSplitModel(run.split, run.fcl, limits, from, to, options), 0},
           static_cast<double>(run.obstacles.detector->model()->supportCount()), run.splitQuality,
           obstaclesTrain, 0);
  }
  {  // planned last (it learns, and keeps what it learns for the scene's next queries), listed
     // first. Scored as it plans this query: on its oracle's labels.
    const std::shared_ptr<const Model> model = run.obstacles.detector->model();
    const ConfusionCounts modelQuality = evaluate(*model, run.test, run.obstacleTruth);
    seedPlanners(o.seed, turn);
    addRow({kDefaultMethod,
            pipeline::planOnSceneModel(run.obstacles, run.fcl, limits, from, to, options), 0},
           static_cast<double>(model->supportCount()), modelQuality, obstaclesTrain, 0);
  }
  std::rotate(rows.rbegin(), rows.rbegin() + 1, rows.rend());  // the default method first
  return rows;
}

void runProblem(const Problem& problem, std::size_t p, const RobotDescription& description,
                const MotionBenchOptions& o, const Progress& progress, RobotModels& models,
                PlanRows& results) {
  ProblemRun run = prepareProblem(problem, p, description, o, progress, models, results);
  Rng rng(o.seed * 7919 + p);
  for (std::size_t query = 0; query < o.queriesPerScene; ++query) {
    for (PlanRow& row : planQuery(run, problem, p, query, o, models, rng))
      results.rows.push_back(std::move(row));
  }
}

}  // namespace

PlanRows runMotionBench(const MotionBenchOptions& o, const Progress& progress) {
  if (o.queriesPerScene == 0) throw InvalidArgument("motion-bench: queries per scene must be >= 1");
  PlanRows results;
  std::vector<Problem> problems = problemsIn(o.problems);
  if (o.quick) {  // two problems of each family
    std::map<std::string, std::size_t> kept;
    std::erase_if(problems, [&](const Problem& p) { return ++kept[p.family] > 2; });
  }
  const RobotDescription description =
      loadRobotDescription(o.robot, UrdfOptions{.searchPaths = o.packagePaths}, o.srdf);
  results.warnings = description.warnings;
  if (o.selfModel && !o.selfCollision) {
    throw InvalidArgument("motion-bench: a self-collision model needs self-collision checked");
  }
  RobotModels models;
  for (std::size_t p = 0; p < problems.size(); ++p) {
    const Problem& problem = problems[p];
    if (progress)
      progress("motion-bench: " + progressLine("problem", p, problems.size()) + " (" +
               problem.family + "/" + problem.scene.filename().string() + ")");
    try {
      runProblem(problem, p, description, o, progress, models, results);
    } catch (const std::exception& e) {  // recorded; the other problems still run
      results.skipped.push_back({{{"family", problem.family},
                                  {"problem", problem.id},
                                  {"query", "0"},
                                  {"group", ""},
                                  {"note", ""}},
                                 e.what()});
      if (progress) progress("motion-bench: skipped " + problem.id + ": " + e.what());
    }
    writeRowsSoFar(results, o.resultsFile);
  }
  return results;
}

/// The report's opening: the robot, the models' training, the planner, the methods.
std::string reportPreamble(const MotionBenchOptions& o) {
  std::ostringstream md;
  const PlannerOptions planner = plannerOptions(o, PlannerType::RrtConnect);
  md << "# MoveIt benchmark problems (" << o.problems.string() << ")\n\n"
     << featureSentence(o.features) << " Robot " << o.robot
     << (o.srdf.empty() ? "" : " with the disabled collisions of " + o.srdf.string())
     << (o.selfCollision ? ", self-collision checked by FCL" : ", self-collision not checked")
     << "; for each problem the models are trained on the scene (" << trainingSamples(o)
     << " samples, then " << trainingUpdates(o) << " active-learning updates"
     << (o.gamma ? ", gamma " + cell(*o.gamma) : "") << (o.beta ? ", beta " + cell(*o.beta) : "")
     << ") and RRT-Connect plans with each method, " << o.queriesPerScene << " quer"
     << (o.queriesPerScene == 1 ? "y" : "ies")
     << " per scene (the request, then start/goal pairs drawn free under FCL, the goal's joints of "
        "more than a turn taken the turn nearest the start's). Edges checked "
        "every "
     << edgeSteps(o, "rad") << ", range "
     << describeRange(plannerOptions(o, PlannerType::RrtConnect), "rad") << ", time limit "
     << o.timeLimit << " s, seed " << o.seed << (o.quick ? ", quick mode" : "") << ". "
     << simplificationSentence(o.simplifyTime, o.simplification)
     << " Plan times exclude training; the end-to-end lines add each scene's training, shared by "
        "its queries."
     << (o.learnFromVerification
             ? " Before each query after a scene's first, the paper's model learns the exact "
               "answers of the last plan's verification and repair that it got wrong (no oracle "
               "call; learn_s in results.csv, not in the totals)."
             : "")
     << "\n\n"
     << "Default method: " << kDefaultMethod
     << " (what `fastron plan` does): a model of the scene's obstacles "
     << (o.selfCollision ? "alone (self-collisions left to verification, and learned from it)"
                         : "(FCL's labels)")
     << "; when it finds no path within "
     << durationText(std::min(planner.verify.approximateShare, planner.verify.modelShare) *
                     planner.timeLimit)
     << ", a hybrid asking FCL" << (o.selfCollision ? " without self-collision" : "")
     << " about each \"collides\" plans with half the planner's range; its path is verified and "
        "repaired with FCL"
     << (planner.verify.learningRounds > 0 ? ", learning what verification finds it got wrong first"
                                           : "")
     << ". Fastron (paper) and Hybrid (paper): the paper's recipe, a model of everything FCL "
        "checks with a calibrated band (Hybrid asks FCL inside it), verified and repaired with "
        "FCL."
     << (o.selfModel
             ? " Fastron split: the default method's obstacle model beside a "
               "self-collision model learned once for the robot, then the hybrid asking FCL about "
               "their \"collides\", verified and repaired."
             : "")
     << "\n";
  return md.str();
}

/// The planning groups, the warnings, the problems run and the ones skipped, with why.
std::string runSummary(const PlanRows& r) {
  std::ostringstream md;
  std::vector<std::string> groups;
  for (const PlanRow& row : r.rows) {
    const std::string& group = row.queryValue("group");
    if (std::find(groups.begin(), groups.end(), group) == groups.end()) groups.push_back(group);
  }
  std::string groupList;
  for (const std::string& g : groups) groupList += (groupList.empty() ? "" : ", ") + g;
  md << "\nPlanning group" << (groups.size() == 1 ? "" : "s") << " (the requests' group_name; "
     << "'-' for none, the robot's actuated joints): " << (groupList.empty() ? "none" : groupList)
     << ".\n";
  for (const std::string& note : r.notes) md << "\n" << note << "\n";
  if (!r.warnings.empty()) {
    md << "\nWarnings (" << r.warnings.size() << "; the run went on past them):\n\n";
    for (const std::string& w : r.warnings) md << "- " << w << "\n";
  }
  const std::size_t problemCount = [&] {
    std::vector<std::string> seen;
    for (const PlanRow& row : r.rows) {
      const std::string key = row.queryValue("family") + "/" + row.queryValue("problem");
      if (std::find(seen.begin(), seen.end(), key) == seen.end()) seen.push_back(key);
    }
    return seen.size();
  }();
  md << "\nProblems run: " << problemCount << "; skipped: " << r.skipped.size() << ".\n";
  if (!r.skipped.empty()) {
    md << "\n| Family | Problem | Why it was skipped |\n|---|---|---|\n";
    for (const SkippedQuery& q : r.skipped) {
      std::string why = q.error;
      std::replace(why.begin(), why.end(), '|', '/');
      md << "| " << q.query[0].second << " | " << q.query[1].second << " | " << why << " |\n";
    }
  }
  return md.str();
}

using experiments::RowFilter;
using RowValue = std::function<double(const PlanRow&)>;

/// The median (or mean) of `value` over the rows matching `where`.
double statistic(const PlanRows& r, const RowFilter& where, const RowValue& value, bool median) {
  std::vector<double> values;
  for (const PlanRow& row : r.rows) {
    if (!where || where(row)) values.push_back(value(row));
  }
  const Summary s = summarize(values);
  return median ? s.median : s.mean;
}

RowValue figure(const char* name) {
  return [name](const PlanRow& row) { return row.figure(name); };
}

/// The rows of `method` matching `where` that hold a scene's training, once: its first query's.
RowFilter firstQueryOf(const RowFilter& where, const char* method) {
  return [where, method](const PlanRow& row) {
    return (!where || where(row)) && row.method == method && row.queryValue("query") == "0";
  };
}

/// A method's model over the scenes: medians of training time and |S|, means of accuracy and TPR
/// (each scene's first query, as trained).
std::string modelLine(const PlanRows& r, const RowFilter& where, const char* method,
                      const std::string& labels) {
  const RowFilter first = firstQueryOf(where, method);
  char line[400];
  std::snprintf(line, sizeof line,
                "- %s: trained in a median %s, |S| median %.0f, accuracy %.3f and TPR %.3f "
                "(means over scenes; %s).\n",
                method, durationText(statistic(r, first, figure("train_s"), true)).c_str(),
                statistic(r, first, figure("support"), true),
                statistic(r, first, figure("accuracy"), false),
                statistic(r, first, figure("tpr"), false), labels.c_str());
  return std::string(line);
}

/// "Models per scene": each method's models, as trained.
std::string modelsPerScene(const PlanRows& r, const MotionBenchOptions& o, const RowFilter& where) {
  std::ostringstream out;
  char sample[160];
  std::snprintf(sample, sizeof sample, "against FCL on %zu fresh uniform configurations per scene",
                testPoints(o));
  const RowFilter firstOfDefault = firstQueryOf(where, kDefaultMethod);
  std::size_t scenes = 0, cover = 0;
  for (const PlanRow& row : r.rows) {
    if (!firstOfDefault(row)) continue;
    ++scenes;
    if (row.figure("cover_rule") > 0) ++cover;
  }
  out << "\nModels per scene:\n"
      << modelLine(
             r, where, kDefaultMethod,
             o.selfCollision ? "on the obstacles' labels, FCL without self-collision" : sample);
  if (o.features == FeatureKind::Kinematic) {
    out << "  (its control points chosen on the robot's first scene on "
        << pipeline::SceneModelOptions{}.heldOut
        << " held-out labels, that scene's training included, and kept for its others: the "
           "spread rule's in "
        << scenes - cover << " scenes, the cover rule's in " << cover << ")\n";
  }
  out << modelLine(r, where, "Fastron (paper)", sample);
  if (std::any_of(r.rows.begin(), r.rows.end(), firstQueryOf(where, "Fastron split"))) {
    out << modelLine(r, where, "Fastron split",
                     "with the self-collision model, against FCL with self-collision")
        << "  (the robot's self-collision model: learned once for the robot and kept in the "
           "cache, not counted per scene; "
        <<
        [&] {
          const double s =
              statistic(r, firstQueryOf(where, "Fastron split"), figure("self_train_s"), true);
          return s > 0 ? "trained in " + durationText(s) : std::string("read from it");
        }()
        << ")\n";
  }
  return out.str();
}

/// Along FCL's own paths of the requests, and the default method's learning rounds.
std::string alongFclPaths(const PlanRows& r, const MotionBenchOptions& o, const RowFilter& where) {
  std::ostringstream out;
  const PlannerOptions planner = plannerOptions(o, PlannerType::RrtConnect);
  // Along FCL's paths of the requests (NaN where FCL found none).
  const auto along = [&](const char* name) {
    std::vector<double> values;
    for (const PlanRow& row : r.rows) {
      if (firstQueryOf(where, "FCL")(row) && !std::isnan(row.figure(name))) {
        values.push_back(row.figure(name));
      }
    }
    return values.empty() ? std::numeric_limits<double>::quiet_NaN() : summarize(values).median;
  };
  char line[400];
  std::snprintf(line, sizeof line,
                "\nAlong FCL's own path of each request (its states every %g rad, all free): a "
                "median %.0f%% of them within %.0f cm of an obstacle, and the default method's "
                "model calls a median %.0f%% of them colliding.\n",
                o.resolution, 100 * along("fcl_path_near_walls"), 100 * kNearWalls,
                100 * along("fcl_path_called_colliding"));
  out << line;
  const auto relearned = [](const PlanRow& row) {
    return static_cast<double>(row.outcome.relearned);
  };
  if (planner.verify.learningRounds > 0) {
    std::snprintf(line, sizeof line,
                  "When verification finds its path colliding, %s learns the answers it got "
                  "wrong and plans again, up to %u times (mean %.2f times a query).\n",
                  kDefaultMethod, planner.verify.learningRounds,
                  statistic(
                      r,
                      [&](const PlanRow& row) {
                        return (!where || where(row)) && row.method == kDefaultMethod;
                      },
                      relearned, false));
    out << line;
  }
  return out.str();
}

/// Per family, and over all: the plan table, speed-ups without and with training, where the time
/// goes, the models, and what FCL's paths say.
std::string familySummary(const PlanRows& r, const MotionBenchOptions& o, const RowFilter& where) {
  std::ostringstream out;
  out << planTable(r, where, {"RRTConnect"}) << speedups(r, where, {"RRTConnect"})
      << endToEndSpeedups(r, where, 1);
  if (o.queriesPerScene > 1) out << endToEndSpeedups(r, where, o.queriesPerScene);
  out << "\nWhere the time goes (medians over solved plans):\n\n"
      << timeBreakdown(r, where, {"RRTConnect"}) << modelsPerScene(r, o, where)
      << alongFclPaths(r, o, where);
  return out.str();
}

/// "The requests": every method's plan of each request.
std::string requestsTable(const PlanRows& r) {
  std::ostringstream md;
  md << "\n## The requests\n\n"
     << "| Family | Problem | Method | Status | Plan | Verify | Repair | Total | Path length | "
        "Collides (FCL) | Training | Note |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  const auto ms = [](double seconds) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f ms", seconds * 1e3);
    return std::string(buffer);
  };
  for (const PlanRow& row : r.rows) {
    if (row.queryValue("query") != "0") continue;
    const PlanOutcome& plan = row.outcome;
    char length[32];
    std::snprintf(length, sizeof length, "%.3f", plan.pathLength);
    const std::string collides =
        plan.collidesUnderAudit ? (*plan.collidesUnderAudit ? "1" : "0") : "nan";
    md << "| " << row.queryValue("family") << " | " << row.queryValue("problem") << " | "
       << row.method << " | " << plan.status << " | " << ms(plan.planSeconds) << " | "
       << ms(plan.verifySeconds) << " | " << ms(plan.repairSeconds) << " | "
       << ms(plan.totalSeconds) << " | " << length << " | " << collides << " | "
       << (row.method != "FCL" ? ms(row.figure("train_s")) : "—") << " | " << row.queryValue("note")
       << " |\n";
  }
  return md.str();
}

std::string motionBenchReport(const PlanRows& r, const MotionBenchOptions& o) {
  std::ostringstream md;
  md << reportPreamble(o) << runSummary(r);
  std::vector<std::string> families;
  for (const PlanRow& row : r.rows) {
    const std::string& family = row.queryValue("family");
    if (std::find(families.begin(), families.end(), family) == families.end()) {
      families.push_back(family);
    }
  }
  for (const std::string& family : families) {
    md << "\n## " << family << "\n\n"
       << familySummary(r, o,
                        [&](const PlanRow& row) { return row.queryValue("family") == family; });
  }
  md << "\n## All families\n\n" << familySummary(r, o, {}) << requestsTable(r);
  return md.str();
}

}  // namespace fastron::experiments
