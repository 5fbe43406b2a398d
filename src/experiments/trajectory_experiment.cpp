#include "fastron/experiments/trajectory_experiment.h"

#include <iomanip>
#include <sstream>

#include "baxter_cases.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/metrics.h"
#include "fastron/experiments/report_text.h"
#include "fastron/experiments/statistics.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/labelling.h"
#include "plan_rows.h"

namespace fastron::experiments {

namespace {

constexpr const char* kCase = "7dof-3boxes";

/// Ends on opposite sides of the workspace, both free under `fcl`, whose straight line collides.
std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>> endsThroughAnObstacle(
    const JointLimits& limits, const CollisionChecker& fcl, Rng& rng, double resolution) {
  for (int attempt = 0; attempt < 200; ++attempt) {
    auto ends = tryOppositeEnds(limits, fcl, rng, 1000);
    if (ends && !checkPath(fcl, {ends->first, ends->second}, resolution).valid()) return ends;
  }
  return std::nullopt;
}

/// The model's score at every state of `path` at `resolution`, against the share of its length.
void addScores(Table& scores, std::size_t trial, const std::string& which, const Model& model,
               const JointPath& path, double resolution) {
  const Configurations states = statesAlongPath(path, resolution);
  const Eigen::VectorXd f = model.scoreBatch(states);
  double travelled = 0;
  const double length = pathLength(path);
  for (Eigen::Index i = 0; i < states.rows(); ++i) {
    if (i > 0) travelled += (states.row(i) - states.row(i - 1)).norm();
    scores.add(
        {std::to_string(trial), which, cell(length > 0 ? travelled / length : 0), cell(f[i])});
  }
}

/// The median of `values` with `digits` decimals, "-" when there are none.
std::string median(const std::vector<double>& values, int digits) {
  if (values.empty()) return "-";
  std::ostringstream text;
  text << std::fixed << std::setprecision(digits) << summarize(values).median;
  return text.str();
}

}  // namespace

TrajectoryResults runTrajectories(const TrajectoryExperimentOptions& o, const Progress& progress) {
  TrajectoryResults out;
  out.results.columns = {"trial",     "method",    "solved",           "time_ms",    "learn_ms",
                         "repair_ms", "stretches", "gradient_repairs", "iterations", "rounds",
                         "length",    "colliding", "support",          "accuracy",   "tpr"};
  out.scores.columns = {"trial", "path", "s", "score"};
  const auto c = caseFor(kCase);
  const Robot robot = baxterWithJoints(c.joints);
  const JointLimits limits = robot.limits();
  const std::uint64_t seed = o.seed * 1000 + c.joints;
  Scene scene = sceneForTrial(c.scene, seed);
  auto fcl = makeSceneChecker("fcl", robot, scene);
  const auto audit = makeSceneChecker("fcl", robot, scene);
  ProxyCollisionDetector proxy(fcl, robotFeatures(robot, o.features),
                               proxyParams(c, seed, o.features));
  proxy.initialize(3000);  // quick too: the optimiser is as good as the model it pushes on
  Rng rng(seed);
  const PlannerOptions options = plannerOptions(o, PlannerType::RrtConnect);
  for (std::size_t trial = 0; trial < o.trials; ++trial) {
    if (progress) progress("optimize, " + progressLine("trial", trial, o.trials));
    scene.step(5);
    fcl->setScene(scene);
    audit->setScene(scene);
    for (int update = 0; update < 5; ++update) proxy.step();
    const std::shared_ptr<const Model> model = proxy.model();
    const Configurations test = uniformConfigurations(limits, o.quick ? 300 : 1000, rng);
    const ConfusionCounts counts = evaluate(*model, test, labelConfigurations(*audit, test, 1));
    const auto ends = endsThroughAnObstacle(limits, *fcl, rng, o.resolution);
    if (!ends) continue;
    const auto& [start, goal] = *ends;
    // One row; `plan` gives the repair figures of the sampling planners.
    const auto add = [&](const std::string& method, bool solved, std::chrono::nanoseconds time,
                         std::chrono::nanoseconds learn, std::size_t iterations, std::size_t rounds,
                         const JointPath& path, const VerifiedPlan& plan) {
      const bool colliding = solved && !checkPath(*audit, path, o.resolution / 3).valid();
      out.results.add(
          {std::to_string(trial), method, solved ? "1" : "0", cell(1e3 * inSeconds(time)),
           cell(1e3 * inSeconds(learn)), cell(1e3 * inSeconds(plan.repairTime)),
           std::to_string(plan.invalidStretches), std::to_string(plan.gradientRepairs),
           std::to_string(iterations), std::to_string(rounds), cell(solved ? pathLength(path) : 0),
           colliding ? "1" : "0", std::to_string(model->supportCount()), cell(counts.accuracy()),
           cell(counts.tpr())});
    };
    const VerifiedTrajectory optimized =
        optimizeVerified(proxy, fcl, start, goal, o.resolution, o.optimizer, o.rounds);
    add("Optimizer", optimized.status == PlanStatus::Solved, optimized.totalTime(),
        optimized.learnTime, optimized.iterations, optimized.rounds, optimized.path, {});
    const std::shared_ptr<const Model> learned = proxy.model();
    addScores(out.scores, trial, "before", *learned, {start, goal}, o.resolution);
    addScores(out.scores, trial, "after", *learned, optimized.path, o.resolution);
    const VerifiedPlan exact = planExactly(fcl, limits, start, goal, options);
    add("FCL", exact.solved(), exact.totalTime(), {}, 0, 0, exact.path, exact);
    const VerifiedPlan fastron = planVerifiedLearning(proxy, fcl, limits, start, goal, options);
    add("Fastron", fastron.solved(), fastron.totalTime(), fastron.learnTime, 0, 0, fastron.path,
        fastron);
  }
  return out;
}

std::string trajectoryReport(const TrajectoryResults& r, const TrajectoryExperimentOptions& o) {
  const Table& t = r.results;
  std::ostringstream md;
  md << "# Trajectory optimisation on the model's collision cost\n\n"
     << featureSentence(o.features)
     << " Baxter's right arm (7 joints) among the paper's three random-walk boxes; before each "
        "query the boxes move 5 steps and the model makes 5 updates. Start and goal are free, on "
        "opposite sides of the workspace, and their straight line collides under FCL. "
        "'Optimizer' starts from that straight line (waypoints "
     << o.optimizer.spacing << " rad apart, margin " << o.optimizer.margin << ", step "
     << o.optimizer.maxStep << " rad, smoothing " << o.optimizer.smoothing
     << ") and is verified with FCL every " << o.resolution
     << " rad, the model learning what verification finds (up to " << o.rounds
     << " times); it runs first, so "
        "the others' model has learned its answers too. 'FCL' is RRT-Connect on FCL, 'Fastron' "
        "RRT-Connect on the model with verify and repair, both simplified ("
     << simplificationSentence(o.simplifyTime, o.simplification)
     << "). 'Colliding' re-checks every final path with a separate FCL at a third of the step. "
     << t.distinct("trial").size() << " queries, seed " << o.seed << (o.quick ? ", quick" : "")
     << ".\n\n| method | solved | time (ms), median | iterations, median | rounds, median | "
        "length (rad), median | colliding |\n|---|---|---|---|---|---|---|\n";
  for (const std::string& method : t.distinct("method")) {
    const Table::Filter solved{{"method", method}, {"solved", "1"}};
    const std::size_t n = t.numbers("solved", {{"method", method}}).size();
    const std::vector<double> colliding = t.numbers("colliding", solved);
    double collidingCount = 0;
    for (const double each : colliding) collidingCount += each;
    md << "| " << method << " | " << t.numbers("time_ms", solved).size() << " of " << n << " | "
       << median(t.numbers("time_ms", solved), 2) << " | "
       << median(t.numbers("iterations", solved), 0) << " | "
       << median(t.numbers("rounds", solved), 0) << " | " << median(t.numbers("length", solved), 2)
       << " | " << collidingCount << " |\n";
  }
  md << "\nModel (per query, against FCL on fresh uniform configurations): |S| "
     << meanStd(summarize(t.numbers("support", {{"method", "Optimizer"}})), 0) << ", accuracy "
     << meanStd(summarize(t.numbers("accuracy", {{"method", "Optimizer"}})), 3) << ", TPR "
     << meanStd(summarize(t.numbers("tpr", {{"method", "Optimizer"}})), 3) << ".\n";
  return md.str();
}

}  // namespace fastron::experiments
