// fastron plan: one planning query from the command line, on a shipped robot or a URDF among a
// scene, with Fastron (verified and repaired with FCL), GJK (verified and repaired) or FCL.
// Exit 0 with a valid path, 1 without one, 2 on an error.

#include <ompl/util/RandomNumbers.h>
#include <chrono>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "fastron/core/error.h"
#include "fastron/core/model_checker.h"
#include "fastron/core/model_file.h"
#include "fastron/experiments/statistics.h"
#include "fastron/geometry/moveit_request.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/pipeline/scene_model.h"
#include "fastron/pipeline/self_model.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/proxy_collision_detector.h"
#include "report_format.h"
#include "robot_options.h"
#include "scene_options.h"

namespace fastron::cli {

void addSimplificationOption(CLI::App& cmd, std::function<void(PathSimplification)> set,
                             const std::string& scope) {
  const std::vector<std::string> names{simplificationName(PathSimplification::Full),
                                       simplificationName(PathSimplification::Shortcuts)};
  cmd.add_option_function<std::string>(
         "--simplification",
         [set = std::move(set)](const std::string& name) { set(parsePathSimplification(name)); },
         scope + names[0] +
             " (OMPL's simplify, with B-spline smoothing, as MoveIt; the default) or " + names[1] +
             " (shortcutting and vertex reduction alone, fewer checks), every checker alike")
      ->check(CLI::IsMember(names, CLI::ignore_case));
}

using namespace experiments;  // the command runs the experiments layer
namespace {

struct PlanOptions {
  RobotOptions robot;
  SceneOptions scene;  // its checker verifies, and labels the samples of a model trained here
  std::string request, model, selfModel, out, checker = "fastron", planner = "RRTConnect";
  std::vector<double> start, goal;
  FeatureOptions features;
  // pipeline::SceneModelOptions' defaults: bench motion-bench measured them (docs/planning.md).
  std::size_t samples = pipeline::SceneModelOptions{}.samples,
              updates = pipeline::SceneModelOptions{}.updates;
  unsigned learningRounds = PlannerOptions{}.verify.learningRounds;
  std::optional<double> gamma, beta;
  double resolution = 0.03, modelResolution = 0, timeLimit = 10, simplifyTime = 0.1, range = 0;
  std::size_t rangeStage = PlannerOptions{}.rangeStage;
  std::uint64_t seed = 1;
  PathSimplification simplification = PathSimplification::Full;
};

/// "Fastron: no path within the time limit (1.70 ms, 812 checks in 0.61 ms); Fastron+FCL: solved
/// (48.2 ms, 20311 checks in 40.1 ms, of which simplify 3.58 ms)": where the planning time went.
std::string attemptsText(const std::vector<PlanAttempt>& attempts) {
  std::ostringstream text;
  for (std::size_t i = 0; i < attempts.size(); ++i) {
    const PlanAttempt& a = attempts[i];
    text << (i > 0 ? "; " : "") << a.source << ": " << toString(a.status) << " ("
         << durationText(inSeconds(a.time)) << ", " << a.checks << " checks in "
         << durationText(inSeconds(a.checkTime));
    if (a.simplifyTime.count() > 0)
      text << ", of which simplify " << durationText(inSeconds(a.simplifyTime));
    if (a.substituteEnds) text << ", between substitute ends";
    text << ')';
  }
  return attempts.empty() ? "none" : text.str();
}

/// Why `q` is not free under `exact`, e.g. "right_hand touches box", or "" when it is free.
std::string contactAt(const SceneChecker& exact, const Eigen::VectorXd& q) {
  const auto contact =
      exact.firstContact(std::span<const double>(q.data(), static_cast<std::size_t>(q.size())));
  return contact ? describe(*contact) : "";
}

/// A model file read for `robot`, reported on one line under `label`.
std::shared_ptr<const Model> readModel(const std::string& path, const Robot& robot,
                                       const char* label) {
  const auto model = withFastestAnswers(std::make_shared<const Model>(loadModelFor(path, robot)));
  std::cout << label << path << ", " << model->supportCount() << " support points, features "
            << model->features().summary();
  if (const PointField* field = model->pointField()) {
    std::cout << ", answered by a point field of " << field->grids().size() << " grids of "
              << field->spacing() * 100 << " cm cells, answers " << toString(field->answers());
  }
  std::cout << '\n';
  return model;
}

/// The model of the scene's obstacles (pipeline::trainSceneModel), reported on one line.
pipeline::SceneModel trainObstacleModel(const PlanOptions& o, const Robot& robot,
                                        const Scene& scene) {
  // Control points left to the defaults: the model chooses between the automatic rules.
  const bool choose =
      o.features.controlLinks.empty() && o.features.automatic == ControlPointOptions{};
  const std::vector<pipeline::FeatureCandidate> candidates =
      choose ? pipeline::automaticFeatureCandidates(robot, parseFeatureKind(o.features.kind))
             : std::vector<pipeline::FeatureCandidate>{
                   {"given", featuresFromOptions(o.features, robot)}};
  pipeline::SceneModel model =
      pipeline::trainSceneModel(robot, scene, checkerOptionsFrom(o.scene), candidates,
                                {.samples = o.samples,
                                 .updates = o.updates,
                                 .seed = o.seed,
                                 .gamma = o.gamma,
                                 .beta = o.beta,
                                 .checker = o.scene.checker});
  std::cout << "model    " << (o.scene.selfCollision ? "of the obstacles, " : "") << "trained on "
            << o.samples << " samples labelled by " << model.oracle->name() << " and " << o.updates
            << " active-learning updates in " << durationText(model.trainSeconds) << ", "
            << model.detector->model()->supportCount() << " support points, features "
            << model.detector->features().summary();
  if (!model.candidates.empty()) {
    std::cout << ", control points of the " << model.candidates[model.chosen].name
              << " rule (held-out accuracy, TPR:";
    for (const pipeline::CandidateScore& c : model.candidates) {
      std::cout << ' ' << c.name << ' ' << rate(c.accuracy) << ' ' << rate(c.tpr);
    }
    std::cout << ')';
  }
  std::cout << '\n';
  return model;
}

/// --self-model: plans on the scene's obstacle model (read with --model, or trained here on the
/// exact checker without self-collisions) and the robot's self-collision model together, and
/// verifies and repairs with `exact`, which checks both. (No band: the pair has none to plan a
/// hybrid on.)
VerifiedPlan planWithSelfModel(const PlanOptions& o, const Robot& robot, const Scene& scene,
                               const std::shared_ptr<const SceneChecker>& exact,
                               const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                               const PlannerOptions& options) {
  std::shared_ptr<const Model> self;
  if (o.selfModel == "auto") {  // learned once for the robot, kept in the cache
    const pipeline::SelfModel cached =
        pipeline::selfCollisionModel(robot, {.padding = o.scene.padding, .cacheDirectory = {}});
    self = cached.model;
    std::cout << "self     " << cached.file.string() << ", "
              << (cached.fromCache ? std::string("read from the cache")
                                   : "trained in " + durationText(cached.trainSeconds) +
                                         " and kept in the cache")
              << ", " << self->supportCount() << " support points, features joints\n";
  } else {
    self = readModel(o.selfModel, robot, "self     ");
  }
  const auto obstacles = !o.model.empty() ? readModel(o.model, robot, "model    ")
                                          : trainObstacleModel(o, robot, scene).detector->model();
  return pipeline::planOnSplitModel(
      pipeline::splitModel(obstacles, pipeline::selfModelChecker(robot, self)), exact,
      robot.limits(), start, goal, options);
}

/// The robot to plan (the request's group, unless --joints or --group chose the joints; other
/// joints where the scene and the start state put them) and the query's ends.
struct PlanQuery {
  Robot robot;
  Eigen::VectorXd start, goal;
  std::string group;  ///< the SRDF group planned, or empty for the robot's actuated joints
};

PlanQuery planQuery(const PlanOptions& o, const Scene& scene) {
  RobotDescription description = robotDescriptionFromOptions(o.robot);
  if (o.request.empty()) {
    if (o.start.empty() || o.goal.empty())
      throw InvalidArgument("give --start and --goal (or --request with a MoveIt request)");
    PlanQuery query{std::move(description.robot), {}, {}, o.robot.group};
    query.start = configurationFromOption(o.start, query.robot, "--start");
    query.goal = configurationFromOption(o.goal, query.robot, "--goal");
    return query;
  }
  if (!o.start.empty() || !o.goal.empty())
    throw InvalidArgument("give either --request or --start and --goal, not both");
  const PlanRequest request = loadMoveItRequest(o.request);
  const bool jointsChosen = !o.robot.joints.empty() || !o.robot.group.empty();
  RequestRobot forRequest = robotForRequest(
      std::move(description.robot),
      jointsChosen ? std::vector<SrdfGroup>{} : description.srdf.groups, scene, request, o.request);
  if (!forRequest.warning.empty()) std::cerr << "fastron: warning: " << forRequest.warning << '\n';
  RequestEnds ends = requestEnds(forRequest.robot, request, o.request);
  const std::string group = jointsChosen                 ? o.robot.group
                            : forRequest.warning.empty() ? request.group
                                                         : std::string();
  return {std::move(forRequest.robot), std::move(ends.start), std::move(ends.goal), group};
}

/// The plan of the method --checker names: an exact checker's (verified with `exact` when it is
/// another), or Fastron's (with --self-model, a --model file, or the default method).
VerifiedPlan planByMethod(const PlanOptions& o, const PlanQuery& q, const Scene& scene,
                          const CheckerOptions& checking,
                          const std::shared_ptr<const SceneChecker>& exact,
                          const PlannerOptions& options) {
  const JointLimits limits = q.robot.limits();
  if (o.checker == o.scene.checker) return planExactly(exact, limits, q.start, q.goal, options);
  if (o.checker != "fastron") {  // another exact checker, verified with `exact`
    const auto other = makeSceneChecker(o.checker, q.robot, scene, checking);
    return planVerified(other, exact, limits, q.start, q.goal, options);
  }
  if (!o.selfModel.empty())
    return planWithSelfModel(o, q.robot, scene, exact, q.start, q.goal, options);
  if (!o.model.empty()) {
    // A model read from a file has no calibrated band: the planner falls back from it to `exact`
    // directly.
    return planVerified(CalibratedModel{readModel(o.model, q.robot, "model    "), {}, 0}, exact,
                        limits, q.start, q.goal, options);
  }
  // The default method (pipeline/scene_model.h; bench motion-bench's "Fastron"): a model of the
  // obstacles alone, self-collisions, when checked, left to verification; with --learning-rounds
  // N it learns what verification found it got wrong and plans again before repairing.
  pipeline::SceneModel model = trainObstacleModel(o, q.robot, scene);
  PlannerOptions learning = options;
  learning.verify.learningRounds = o.learningRounds;
  return pipeline::planOnSceneModel(model, exact, limits, q.start, q.goal, learning);
}

/// The plan's report: what planned, its status, where the time went, the checks, the path.
void printPlan(const PlanOptions& o, const VerifiedPlan& plan, const SceneChecker& exact,
               const PlannerOptions& options) {
  std::cout << "planner  " << plannerName(options.type) << " on " << o.checker
            << (o.checker == o.scene.checker ? "" : ", verified and repaired with " + exact.name())
            << '\n'
            << "path of  " << plan.plannedOn << '\n'
            << "status   " << (plan.solved() ? "solved" : plan.failure) << '\n'
            << "time     plan " << durationText(inSeconds(plan.planTime)) << " (of which simplify "
            << durationText(inSeconds(plan.simplifyTime)) << ", "
            << simplificationName(options.simplification) << "), verify "
            << durationText(inSeconds(plan.verifyTime)) << ", repair "
            << durationText(inSeconds(plan.repairTime)) << ", total "
            << durationText(inSeconds(plan.totalTime())) << '\n';
  std::cout << "plans    " << attemptsText(plan.attempts) << '\n'
            << "checks   " << exact.name() << " " << plan.exactChecks;
  if (plan.relaxedChecks > 0) {
    std::cout << "; the model's oracle (" << exact.name() << ", obstacles only) "
              << plan.relaxedChecks;
  }
  std::cout << '\n';
  if (!plan.solved()) return;
  std::cout << "path     " << plan.path.size() << " waypoints, length " << std::setprecision(4)
            << pathLength(plan.path) << " (joint space), " << plan.invalidStretches
            << " stretch(es) repaired";
  if (plan.relearned > 0) {
    std::cout << ", the model learned from verification " << plan.relearned << " time(s) first";
  }
  std::cout << '\n';
}

int runPlan(const PlanOptions& o) {
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(o.seed));
  const Scene scene = sceneFromOptions(o.scene);
  const PlanQuery query = planQuery(o, scene);
  if (!o.selfModel.empty() && !o.scene.selfCollision) {
    throw InvalidArgument(
        "--self-model needs --self-collision: the final path is checked for self-collisions too");
  }
  if (!o.selfModel.empty() && o.checker != "fastron") {
    throw InvalidArgument("--self-model goes with --checker fastron, not " + o.checker);
  }
  const PlannerOptions options{.type = parsePlannerType(o.planner),
                               .range = o.range,
                               .rangeStage = o.rangeStage,
                               .resolution = o.resolution,
                               .modelResolution = o.modelResolution,
                               .timeLimit = o.timeLimit,
                               .simplifyTime = o.simplifyTime,
                               .simplification = o.simplification};
  validate(options);

  std::cout << "robot    " << query.robot.name() << ", " << query.robot.dof() << " actuated joints"
            << (query.group.empty() ? "" : " (group " + query.group + ")") << '\n'
            << "scene    " << o.scene.file << ", " << scene.size() << " obstacle(s)\n";
  const CheckerOptions checking = checkerOptionsFor(o.scene, query.robot, "tables   ");
  const std::shared_ptr<const SceneChecker> exact =
      makeSceneChecker(o.scene.checker, query.robot, scene, checking);
  for (const auto& [what, q] : {std::pair{"start", &query.start}, std::pair{"goal", &query.goal}}) {
    if (const std::string contact = contactAt(*exact, *q); !contact.empty()) {
      std::cout << what << " in collision under " << exact->name() << ": " << contact << '\n';
      return 1;
    }
  }
  const VerifiedPlan plan = planByMethod(o, query, scene, checking, exact, options);
  printPlan(o, plan, *exact, options);
  if (!plan.solved()) return 1;
  if (!o.out.empty()) {
    writePathCsv(plan.path, query.robot.actuatedJointNames(), o.out);
    std::cout << "written  " << o.out << '\n';
  }
  return 0;
}

}  // namespace

void addPlanCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<PlanOptions>();
  CLI::App* cmd = app.add_subcommand(
      "plan", "Plan one motion with Fastron, GJK or FCL (exit 0: valid path, 1: none, 2: error)");
  addRobotOptions(*cmd, o->robot);
  addSceneOptions(*cmd, o->scene,
                  {.checkerRole = "verifies and repairs every path and labels a model's samples",
                   .checkerOption = "--exact"});
  cmd->add_option("--start", o->start, "start joint values, comma-separated")->delimiter(',');
  cmd->add_option("--goal", o->goal, "goal joint values, comma-separated")->delimiter(',');
  cmd->add_option("--request", o->request, "MoveIt MotionPlanRequest YAML with start and goal")
      ->check(CLI::ExistingFile);
  std::vector<std::string> plannedOn{"fastron"};
  for (const SceneCheckerKind& kind : sceneCheckerKinds()) plannedOn.push_back(kind.name);
  cmd->add_option("--checker", o->checker,
                  "what the planner asks: fastron (a model, verified with --exact) or an exact "
                  "checker's name")
      ->capture_default_str()
      ->transform(CLI::IsMember(plannedOn, CLI::ignore_case));
  cmd->add_option("--planner", o->planner, "RRT, RRTConnect, RRT* or BIT*")->capture_default_str();
  cmd->add_option("--model", o->model, "a model file to plan on (default: train one on the scene)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--self-model", o->selfModel,
                  "with --self-collision: a model of the robot's self-collisions (fastron train "
                  "--robot R --self-collision), or 'auto': the robot's own, learned once and "
                  "kept in the cache ($FASTRON_CACHE_DIR, else ~/.cache/fastron); plan on it "
                  "beside a model of the scene's obstacles alone, trained here or given with "
                  "--model")
      ->check(CLI::ExistingFile | CLI::IsMember({"auto"}));
  cmd->add_option("--samples", o->samples, "training samples when no --model is given")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--updates", o->updates, "active-learning updates after them")
      ->capture_default_str();
  cmd->add_option("--learning-rounds", o->learningRounds,
                  "with a model trained here: times it learns what verification found it got "
                  "wrong and plans again before the path is repaired (0: repair at once)")
      ->capture_default_str();
  addFeatureOptions(*cmd, o->features);
  cmd->add_option("--gamma", o->gamma,
                  "kernel width of the trained model (default: 40 for fk features, 5 for joints)")
      ->check(numberAbove(0));
  cmd->add_option("--beta", o->beta,
                  "conditional bias of the trained model (default: 30 for fk, 500 for joints)")
      ->check(numberAbove(1, true));
  cmd->add_option("--resolution", o->resolution, "joint-space step of edge checks")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--model-resolution", o->modelResolution,
                  "joint-space step of edge checks on a Fastron model or its hybrid (default: 3 "
                  "times --resolution; their paths are verified with --exact at --resolution)")
      ->check(numberAbove(0));
  cmd->add_option("--time-limit", o->timeLimit, "seconds per planning query")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--range", o->range,
                  "longest tree edge in joint space to begin with (default: OMPL's, a fifth of "
                  "the diagonal of the joint limits); RRT-Connect halves it after --range-stage "
                  "iterations without a path")
      ->check(numberAbove(0));
  cmd->add_option("--range-stage", o->rangeStage,
                  "RRT-Connect: iterations without a path before its range is halved, down to an "
                  "eighth, then the first range again, each round of ranges twice as long (0: "
                  "the range stays)")
      ->capture_default_str();
  cmd->add_option("--simplify-time", o->simplifyTime,
                  "seconds of OMPL path simplification (0: the planner's path as found)")
      ->capture_default_str()
      ->check(numberAbove(0, true));
  addSimplificationOption(*cmd, [o](PathSimplification s) { o->simplification = s; });
  cmd->add_option("--seed", o->seed, "seed of every random choice")->capture_default_str();
  cmd->add_option("--out", o->out,
                  "write the path as CSV (a header of joint names, a waypoint per row)");
  cmd->callback([o, &exitCode] { exitCode = runPlan(*o); });
}

}  // namespace fastron::cli
