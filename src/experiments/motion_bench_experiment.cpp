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
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/geometry/urdf.h"
#include "fastron/pipeline/scene_model.h"
#include "fastron/pipeline/self_model.h"
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
  return o.trainingPoints.value_or(o.quick ? 1500 : pipeline::SceneModelOptions{}.samples);
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
  std::shared_ptr<const Model> selfModel;  ///< with MotionBenchOptions::selfModel
  double selfTrainSeconds = 0;
};

/// The robot's self-collision model, learned once per robot and kept in the cache
/// (pipeline::selfCollisionModel): self-collision does not depend on the scene.
void learnSelfCollisions(const Robot& robot, const MotionBenchOptions& o, const Progress& progress,
                         RobotModels& models) {
  if (progress) progress("motion-bench: the robot's self-collision model");
  const pipeline::SelfModel self =
      pipeline::selfCollisionModel(robot, {.samples = o.quick ? 2000 : o.selfTrainingPoints,
                                           .updates = trainingUpdates(o),
                                           .seed = o.seed,
                                           .cacheDirectory = o.selfModelCache});
  if (progress)
    progress("motion-bench: self-collision model " +
             std::string(self.fromCache ? "read from " : "trained and kept in ") +
             self.file.string());
  models.selfTrainSeconds = self.trainSeconds;
  models.selfModel = self.model;
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

void runProblem(const Problem& problem, std::size_t p, const RobotDescription& description,
                const MotionBenchOptions& o, const Progress& progress, RobotModels& models,
                PlanRows& results) {
  Scene scene = loadScene(problem.scene);
  const PlanRequest request = loadMoveItRequest(problem.request);
  const RequestRobot forRequest = robotForRequest(description.robot, description.srdf.groups, scene,
                                                  request, problem.request.string());
  if (!forRequest.warning.empty() && std::find(results.warnings.begin(), results.warnings.end(),
                                               forRequest.warning) == results.warnings.end())
    results.warnings.push_back(forRequest.warning);
  const Robot& robot = forRequest.robot;
  if (const std::uint64_t checksum = kinematicsChecksum(robot); checksum != models.checksum) {
    models = {checksum, robotFeatures(robot, o.features), nullptr, 0};
    if (o.selfModel) learnSelfCollisions(robot, o, progress, models);
  }
  const JointLimits limits = robot.limits();
  const FeatureMap& features = models.features;
  const CheckerOptions checking{.selfCollision = o.selfCollision,
                                .proveMotionsFree = !o.denseChecks};
  const std::shared_ptr<const Model>& selfModel = models.selfModel;
  const double selfTrainSeconds = models.selfTrainSeconds;
  const std::size_t samples = trainingSamples(o);
  const std::size_t updates = trainingUpdates(o);
  const RequestEnds ends = requestEnds(robot, request, problem.request.string());
  const Eigen::VectorXd& start = ends.start;
  const Eigen::VectorXd& goal = ends.goal;
  const std::string note = allowGrasp(robot, scene, goal);
  auto fcl = makeSceneChecker("fcl", robot, scene, checking);
  const auto audit = makeSceneChecker("fcl", robot, scene, checking);

  const ProxyParams params =
      withKernelOptions(pipeline::forStaticScene(pipeline::robotProxyParams(
                            o.features, 5, 500, o.seed + p, o.selfCollision)),
                        o);
  ProxyCollisionDetector proxy(fcl, features, params);
  const double trainSeconds = train(proxy, samples, updates);
  CalibratedModel calibrated = proxy.calibratedModel();
  auto support = static_cast<double>(calibrated.model->supportCount());
  // The models' accuracy beside their speed: fresh uniform configurations of this scene,
  // labelled by the audit FCL (self-collision included when it is checked).
  Rng testRng(o.seed * 104729 + p);
  const Configurations test = uniformConfigurations(limits, testPoints(o), testRng);
  const Labels truth = labelConfigurations(*audit, test, 1);
  ConfusionCounts quality = evaluate(*calibrated.model, test, truth);
  // The default method's model (what `fastron plan` trains, pipeline::trainSceneModel): of this
  // scene's obstacles alone (self-collisions, when checked, left to verification and learned
  // from it). With the robot's self-collision model beside it, also the split source.
  pipeline::SceneModel sceneModel = pipeline::trainSceneModel(robot, scene, checking, features,
                                                              {.samples = samples,
                                                               .updates = updates,
                                                               .seed = o.seed + p,
                                                               .gamma = o.gamma,
                                                               .beta = o.beta});
  ProxyCollisionDetector& obstacles = *sceneModel.detector;
  const double obstaclesTrain = sceneModel.trainSeconds;
  const Labels obstacleTruth =  // of `test`, by the model's oracle
      o.selfCollision ? labelConfigurations(*sceneModel.oracle, test, 1) : truth;
  ConfusionCounts splitQuality;
  std::shared_ptr<const CollisionChecker> split;
  const auto obstaclesSupport = static_cast<double>(obstacles.model()->supportCount());
  if (selfModel) {
    split = pipeline::splitModel(obstacles.model(), selfModel);
    const std::vector<std::uint8_t> predicted = split->inCollisionBatch(test);
    splitQuality = confusionOf(truth, [&](std::size_t i) { return predicted[i] != 0; });
  }

  Rng rng(o.seed * 7919 + p);
  const PlannerOptions options = plannerOptions(o, PlannerType::RrtConnect);
  for (std::size_t query = 0; query < o.queriesPerScene; ++query) {
    // Query 0 is the request; the others join two configurations free under FCL.
    const auto freeConfiguration = [&] {
      return sampleFree(
          *fcl, [&] { return uniformIn(limits, rng); }, "configuration");
    };
    const Eigen::VectorXd from = query == 0 ? start : freeConfiguration();
    const Eigen::VectorXd to = query == 0 ? goal : freeConfiguration();
    double learnSeconds = 0;
    if (o.learnFromVerification && query > 0) {  // what the last query's plan taught it
      learnSeconds = std::chrono::duration<double>(proxy.learnObservations().total).count();
      calibrated = proxy.calibratedModel();
      support = static_cast<double>(calibrated.model->supportCount());
      quality = evaluate(*calibrated.model, test, truth);  // each row scores the model it used
    }
    const std::vector<std::pair<std::string, std::string>> queryColumns{
        {"family", problem.family},
        {"problem", problem.id},
        {"query", std::to_string(query)},
        {"group", request.group.empty() ? "-" : request.group},
        {"note", query == 0 ? note : ""}};
    const std::size_t turn = p * o.queriesPerScene + query;
    const std::vector<MethodPlan> plans =
        planWithEachChecker(calibrated, nullptr, fcl, limits, from, to, options, o.seed, turn);
    // Measured on the request only: its distances cost about a second per path on a mesh robot.
    AlongFclPath along;
    if (query == 0) {
      const auto exact = std::find_if(plans.begin(), plans.end(),
                                      [](const MethodPlan& m) { return m.method == "FCL"; });
      if (exact != plans.end()) {
        along = alongFclPath(exact->plan, *obstacles.model(), *audit, o.resolution);
      }
    }
    std::vector<PlanRow> rows;  // the default method's first
    const auto addRow = [&](const MethodPlan& each, double modelSupport,
                            const ConfusionCounts& modelQuality, double trainS, double learnS) {
      rows.push_back({queryColumns,
                      "RRTConnect",
                      each.method,
                      outcomeOf(each, *audit, o.resolution),
                      {{"support", modelSupport},
                       {"accuracy", modelQuality.accuracy()},
                       {"tpr", modelQuality.tpr()},
                       {"train_s", trainS},
                       {"self_train_s", selfTrainSeconds},
                       {"learn_s", learnS},
                       {"fcl_path_near_walls", along.nearWalls},
                       {"fcl_path_called_colliding", along.calledColliding}}});
    };
    for (const MethodPlan& each : plans) {
      if (o.learnFromVerification && each.method == "Fastron") {
        proxy.addObservations(answersMissedBy(*calibrated.model, each.plan.exactAnswers));
      }
      MethodPlan named = each;  // the paper's recipe, beside the default method
      if (each.method != "FCL") named.method = each.method + " (paper)";
      addRow(named, support, quality, trainSeconds, learnSeconds);
    }
    if (split) {
      seedPlanners(o.seed, turn);
      addRow(
          {"Fastron split", pipeline::planOnSplitModel(split, fcl, limits, from, to, options), 0},
          obstaclesSupport, splitQuality, obstaclesTrain, 0);
    }
    {  // planned last (it learns, and keeps what it learns for the scene's next queries), listed
       // first. Scored as it plans this query: on its oracle's labels.
      const std::shared_ptr<const Model> model = obstacles.model();
      const ConfusionCounts modelQuality = evaluate(*model, test, obstacleTruth);
      seedPlanners(o.seed, turn);
      addRow({kDefaultMethod,
              pipeline::planOnSceneModel(sceneModel, fcl, limits, from, to, options), 0},
             static_cast<double>(model->supportCount()), modelQuality, obstaclesTrain, 0);
    }
    results.rows.push_back(std::move(rows.back()));
    rows.pop_back();
    for (PlanRow& row : rows) results.rows.push_back(std::move(row));
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
  results.warnings = description.srdf.warnings;
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

std::string motionBenchReport(const PlanRows& r, const MotionBenchOptions& o) {
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
     << " per scene (the request, then start/goal pairs drawn free under FCL). Edges checked "
        "every "
     << edgeSteps(o, "rad") << ", range "
     << (o.range > 0 ? cell(o.range) + " rad" : std::string("OMPL's default")) << ", time limit "
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
     << durationText(std::min(planner.approximateShare, planner.modelShare) * planner.timeLimit)
     << ", a hybrid asking FCL" << (o.selfCollision ? " without self-collision" : "")
     << " about each \"collides\" plans with half the planner's range; its path is verified and "
        "repaired with FCL"
     << (planner.learningRounds > 0 ? ", learning what verification finds it got wrong first" : "")
     << ". Fastron (paper) and Hybrid (paper): the paper's recipe, a model of everything FCL "
        "checks with a calibrated band (Hybrid asks FCL inside it), verified and repaired with "
        "FCL."
     << (o.selfModel
             ? " Fastron split: the default method's obstacle model beside a "
               "self-collision model learned once for the robot, then the hybrid asking FCL about "
               "their \"collides\", verified and repaired."
             : "")
     << "\n";

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

  using experiments::RowFilter;
  // The median (or mean) of `value` over the rows matching `where`.
  const auto statistic = [&](const RowFilter& where, auto value, bool median) {
    std::vector<double> values;
    for (const PlanRow& row : r.rows) {
      if (!where || where(row)) values.push_back(value(row));
    }
    const Summary s = summarize(values);
    return median ? s.median : s.mean;
  };
  const auto figure = [](const char* name) {
    return [name](const PlanRow& row) { return row.figure(name); };
  };
  // Per family, and over all: medians and means of the total time per valid plan, training per
  // scene, and Fastron's end-to-end time (total + training / queries per scene).
  // Per family, and over all: the plan table, speed-ups without and with training, the models.
  const auto summary = [&](const RowFilter& where) {
    std::ostringstream out;
    out << planTable(r, where, {"RRTConnect"}) << speedups(r, where, {"RRTConnect"})
        << endToEndSpeedups(r, where, 1);
    if (o.queriesPerScene > 1) out << endToEndSpeedups(r, where, o.queriesPerScene);
    out << "\nWhere the time goes (medians over solved plans):\n\n"
        << timeBreakdown(r, where, {"RRTConnect"});
    // A scene's training, once: the rows of its first query.
    const auto firstQueryOf = [&](const char* method) -> RowFilter {
      return [&, method](const PlanRow& row) {
        return (!where || where(row)) && row.method == method && row.queryValue("query") == "0";
      };
    };
    // A method's model over the scenes: medians of training time and |S|, means of accuracy and
    // TPR (each scene's first query, as trained).
    const auto modelLine = [&](const char* method, const char* labels) {
      const RowFilter first = firstQueryOf(method);
      char line[400];
      std::snprintf(line, sizeof line,
                    "- %s: trained in a median %s, |S| median %.0f, accuracy %.3f and TPR %.3f "
                    "(means over scenes; %s).\n",
                    method, durationText(statistic(first, figure("train_s"), true)).c_str(),
                    statistic(first, figure("support"), true),
                    statistic(first, figure("accuracy"), false),
                    statistic(first, figure("tpr"), false), labels);
      return std::string(line);
    };
    char sample[160];
    std::snprintf(sample, sizeof sample,
                  "against FCL on %zu fresh uniform configurations per scene", testPoints(o));
    out << "\nModels per scene:\n"
        << modelLine(kDefaultMethod, o.selfCollision
                                         ? "on the obstacles' labels, FCL without self-collision"
                                         : sample)
        << modelLine("Fastron (paper)", sample);
    if (std::any_of(r.rows.begin(), r.rows.end(), firstQueryOf("Fastron split"))) {
      out << modelLine("Fastron split",
                       "with the self-collision model, against FCL with self-collision")
          << "  (the robot's self-collision model: learned once for the robot and kept in the "
             "cache, not counted per scene; "
          <<
          [&] {
            const double s = statistic(firstQueryOf("Fastron split"), figure("self_train_s"), true);
            return s > 0 ? "trained in " + durationText(s) : std::string("read from it");
          }()
          << ")\n";
    }
    // Along FCL's paths of the requests (NaN where FCL found none).
    const auto along = [&](const char* name) {
      std::vector<double> values;
      for (const PlanRow& row : r.rows) {
        if (firstQueryOf("FCL")(row) && !std::isnan(row.figure(name))) {
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
    if (planner.learningRounds > 0) {
      std::snprintf(line, sizeof line,
                    "When verification finds its path colliding, %s learns the answers it got "
                    "wrong and plans again, up to %u times (mean %.2f times a query).\n",
                    kDefaultMethod, planner.learningRounds,
                    statistic(
                        [&](const PlanRow& row) {
                          return (!where || where(row)) && row.method == kDefaultMethod;
                        },
                        relearned, false));
      out << line;
    }
    return out.str();
  };
  std::vector<std::string> families;
  for (const PlanRow& row : r.rows) {
    const std::string& family = row.queryValue("family");
    if (std::find(families.begin(), families.end(), family) == families.end()) {
      families.push_back(family);
    }
  }
  for (const std::string& family : families) {
    md << "\n## " << family << "\n\n"
       << summary([&](const PlanRow& row) { return row.queryValue("family") == family; });
  }
  md << "\n## All families\n\n" << summary({});

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

}  // namespace fastron::experiments
