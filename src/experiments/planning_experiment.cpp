#include "fastron/experiments/planning_experiment.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <thread>

#include "baxter_cases.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/hybrid_checker.h"
#include "fastron/core/metrics.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/geometry/urdf.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/labelling.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron {
namespace {

using experiments::baxterWithJoints;
using experiments::caseFor;
using experiments::proxyParams;
using experiments::sceneForTrial;
using CheckerPtr = std::shared_ptr<const CollisionChecker>;

const std::vector<std::string> kPlanColumns{"solved",       "status",     "plan_s",   "simplify_s",
                                            "verify_s",     "repair_s",   "total_s",  "path_length",
                                            "waypoints",    "stretches",  "fallback", "exact_ends",
                                            "collides_fcl", "exact_share"};

std::vector<std::string> columnsWith(std::vector<std::string> first,
                                     const std::vector<std::string>& last = {}) {
  first.insert(first.end(), kPlanColumns.begin(), kPlanColumns.end());
  first.insert(first.end(), last.begin(), last.end());
  return first;
}

struct MethodPlan {
  std::string method;
  VerifiedPlan plan;
  /// Of the collision queries of the plan itself (before verification), the share FCL answered.
  double exactShare = 0;
};

/// The plan's cells of a result row; `audit` is an FCL checker the planner never used.
std::vector<std::string> planCells(const MethodPlan& method, const CollisionChecker& audit,
                                   double resolution) {
  const VerifiedPlan& plan = method.plan;
  const bool solved = plan.solved();
  const double collides =
      solved ? (checkPath(audit, plan.path, resolution).valid() ? 0.0 : 1.0) : std::nan("");
  return {solved ? "1" : "0",
          plan.failure.empty() ? toString(plan.status) : plan.failure,
          cell(seconds(plan.planTime)),
          cell(seconds(plan.simplifyTime)),
          cell(seconds(plan.verifyTime)),
          cell(seconds(plan.repairTime)),
          cell(seconds(plan.totalTime())),
          cell(solved ? pathLength(plan.path) : std::nan("")),
          std::to_string(plan.path.size()),
          std::to_string(plan.invalidStretches),
          plan.wholePathReplanned ? "1" : "0",
          plan.substituteEnds ? "1" : "0",
          cell(collides),
          cell(method.exactShare)};
}

std::vector<std::string> joined(std::vector<std::string> first,
                                const std::vector<std::string>& last) {
  first.insert(first.end(), last.begin(), last.end());
  return first;
}

/// Fastron, Hybrid (Fastron with FCL inside the model's calibrated band) and GJK, each verified
/// and repaired with FCL, and FCL itself, on one query. Hybrid only when the band was calibrated.
std::vector<MethodPlan> planWithEachChecker(const CalibratedModel& model, const CheckerPtr& gjk,
                                            const CheckerPtr& fcl, const JointLimits& limits,
                                            const Eigen::VectorXd& start,
                                            const Eigen::VectorXd& goal,
                                            const PlannerOptions& options) {
  std::vector<MethodPlan> plans;
  plans.push_back({"Fastron", planVerified(model.model, fcl, limits, start, goal, options), 0});
  if (model.calibration.colliding + model.calibration.free > 0) {
    const auto hybrid = std::make_shared<HybridChecker>(model.model, fcl, model.calibration.band);
    VerifiedPlan plan = planVerified(hybrid, fcl, limits, start, goal, options);
    plans.push_back({"Hybrid", std::move(plan), hybrid->exactShare()});
  }
  if (gjk) plans.push_back({"GJK", planVerified(gjk, fcl, limits, start, goal, options), 0});
  plans.push_back({"FCL", planExactly(fcl, limits, start, goal, options), 1});
  return plans;
}

bool freeUnder(const CollisionChecker& checker, const Eigen::VectorXd& q) {
  return !checker.inCollision(
      std::span<const double>(q.data(), static_cast<std::size_t>(q.size())));
}

/// A configuration free under `checker` drawn by `sample`; throws Error after `attempts` tries.
template <class Sample>
Eigen::VectorXd sampleFree(const CollisionChecker& checker, Sample&& sample, const char* what,
                           std::size_t attempts = 200000) {
  for (std::size_t i = 0; i < attempts; ++i) {
    const Eigen::VectorXd q = sample();
    if (freeUnder(checker, q)) return q;
  }
  throw Error(std::string("found no collision-free ") + what + " in " + std::to_string(attempts) +
              " samples");
}

Eigen::VectorXd uniformIn(const JointLimits& limits, Rng& rng) {
  return uniformConfigurations(limits, 1, rng).row(0).transpose();
}

/// A uniform configuration for which `reaches` holds; throws Error naming `where` after 10^7 tries.
template <class Reaches>
Eigen::VectorXd sampleReaching(Reaches&& reaches, const JointLimits& limits, Rng& rng,
                               const char* where) {
  for (int i = 0; i < 10'000'000; ++i) {
    Eigen::VectorXd q = uniformIn(limits, rng);
    if (reaches(q)) return q;
  }
  throw Error(std::string("no configuration in 10^7 samples reaches ") + where);
}

/// Start and goal on opposite sides of the workspace: the first joint (the shoulder's yaw) in
/// the lowest and the highest 30% of its range, the others uniform; both free under `fcl`.
std::pair<Eigen::VectorXd, Eigen::VectorXd> oppositeEnds(const JointLimits& limits,
                                                         const CollisionChecker& fcl, Rng& rng) {
  const double lo = limits.lower()[0], hi = limits.upper()[0], band = 0.3 * (hi - lo);
  std::uniform_real_distribution<double> u(0.0, band);
  Eigen::VectorXd start = sampleFree(
      fcl,
      [&] {
        Eigen::VectorXd q = uniformIn(limits, rng);
        q[0] = lo + u(rng);
        return q;
      },
      "start");
  Eigen::VectorXd goal = sampleFree(
      fcl,
      [&] {
        Eigen::VectorXd q = uniformIn(limits, rng);
        q[0] = hi - u(rng);
        return q;
      },
      "goal");
  if (std::uniform_int_distribution<int>(0, 1)(rng) == 1) std::swap(start, goal);
  return {start, goal};
}

std::string progressLine(const std::string& what, std::size_t i, std::size_t n) {
  return what + " " + std::to_string(i + 1) + "/" + std::to_string(n);
}

/// The Markdown table of plan results of the rows matching `where`, one line per (planner,
/// method): success rate, then means ± std over solved plans.
std::string planTable(const Table& r, const Table::Filter& where,
                      const std::vector<std::string>& planners) {
  std::ostringstream md;
  md << "| Planner | Method | Success | Plan (of which simplify) | Verify | Repair | Total | Path "
        "length (joint space) | Repaired stretches | Plans repaired | Plan queries FCL answered | "
        "Final paths colliding (FCL) |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const std::string& planner : planners) {
    for (const std::string& method : r.distinct("method", where)) {
      Table::Filter all = where;
      all.emplace_back("planner", planner);
      all.emplace_back("method", method);
      const std::vector<double> solved = r.numbers("solved", all);
      if (solved.empty()) continue;
      Table::Filter ok = all;
      ok.emplace_back("solved", "1");
      const auto stat = [&](const char* column) { return summarize(r.numbers(column, ok)); };
      const auto solvedCount =
          static_cast<std::size_t>(std::count(solved.begin(), solved.end(), 1.0));
      const std::vector<double> collides = r.numbers("collides_fcl", ok);
      const auto colliding =
          static_cast<std::size_t>(std::count(collides.begin(), collides.end(), 1.0));
      char rate[64];
      std::snprintf(rate, sizeof rate, "%.2f (%zu/%zu)",
                    static_cast<double>(solvedCount) / static_cast<double>(solved.size()),
                    solvedCount, solved.size());
      const std::vector<double> stretches = r.numbers("stretches", ok);
      const auto repaired =
          std::count_if(stretches.begin(), stretches.end(), [](double s) { return s > 0; });
      char repairedShare[64];
      std::snprintf(repairedShare, sizeof repairedShare, "%.0f%%",
                    stretches.empty() ? 0.0
                                      : 100.0 * static_cast<double>(repaired) /
                                            static_cast<double>(stretches.size()));
      md << "| " << planner << " | " << method << " | " << rate << " | "
         << durationMeanStd(stat("plan_s")) << " (" << durationMeanStd(stat("simplify_s")) << ") | "
         << durationMeanStd(stat("verify_s")) << " | " << durationMeanStd(stat("repair_s")) << " | "
         << durationMeanStd(stat("total_s")) << " | " << meanStd(stat("path_length"), 2) << " | "
         << meanStd(stat("stretches"), 2) << " | " << repairedShare << " | "
         << meanStd(summarize(r.numbers("exact_share", all)), 3) << " | " << colliding << " of "
         << collides.size() << " |\n";
    }
  }
  return md.str();
}

/// Per planner, FCL's total time over each other method's, from means and from medians over
/// solved plans.
std::string speedups(const Table& r, const Table::Filter& where,
                     const std::vector<std::string>& planners) {
  std::ostringstream md;
  // Means carry the paper's comparison; medians are not swayed by the odd query that runs into
  // the time limit.
  for (const bool median : {false, true}) {
    md << (median ? "Median" : "\nMean")
       << " total time of FCL / of each method (higher is faster than FCL):";
    for (const std::string& planner : planners) {
      const auto statistic = [&](const std::string& method) {
        Table::Filter filter = where;
        filter.emplace_back("planner", planner);
        filter.emplace_back("method", method);
        filter.emplace_back("solved", "1");
        const Summary s = summarize(r.numbers("total_s", filter));
        return median ? s.median : s.mean;
      };
      const double base = statistic("FCL");
      md << (planner == planners.front() ? " " : "; ") << planner << ":";
      for (const std::string& method : r.distinct("method", where)) {
        if (method == "FCL") continue;
        char buffer[64];
        std::snprintf(buffer, sizeof buffer, " %s %.1fx", method.c_str(), base / statistic(method));
        md << buffer;
      }
    }
    md << ".\n";
  }
  return md.str();
}

std::vector<std::string> plannerNames(const std::vector<PlannerType>& types) {
  std::vector<std::string> names;
  for (const PlannerType t : types) names.push_back(plannerName(t));
  return names;
}

}  // namespace

Table runPlanning(const PlanningOptions& o, const Progress& progress) {
  Table table{columnsWith({"case", "trial", "planner", "method"}, {"support", "accuracy", "tpr"}),
              {}};
  const std::size_t initial = o.quick ? 1000 : 3000;
  const std::size_t testPoints = o.quick ? 300 : 1000;
  for (const std::string& name : o.cases) {
    const auto c = caseFor(name);
    const Robot robot = baxterWithJoints(c.joints);
    const JointLimits limits = robot.limits();
    const std::uint64_t seed = o.seed * 1000 + c.joints;
    Scene scene = sceneForTrial(c.scene, seed);
    auto fcl = std::make_shared<FclChecker>(robot, scene);
    auto gjk = std::make_shared<GjkChecker>(robot, scene);
    FclChecker audit(robot, scene);
    ProxyCollisionDetector proxy(fcl, robotFeatures(robot, o.features),
                                 proxyParams(c, seed, o.features));
    proxy.initialize(initial);
    Rng rng(seed);
    for (std::size_t trial = 0; trial < o.trials; ++trial) {
      if (progress) progress("plan " + name + ", " + progressLine("trial", trial, o.trials));
      // The obstacles move on; the model follows them, then a new query is planned from scratch.
      scene.step(5);
      fcl->setScene(scene);
      gjk->setScene(scene);
      audit.setScene(scene);
      for (int update = 0; update < 5; ++update) proxy.step();
      const CalibratedModel calibrated = proxy.calibratedModel();
      const auto& model = calibrated.model;
      // The model's accuracy beside its speed: fresh configurations, labelled by the audit FCL.
      const Configurations test = uniformConfigurations(limits, testPoints, rng);
      const ConfusionCounts counts = evaluate(*model, test, labelConfigurations(audit, test, 1));
      const auto [start, goal] = oppositeEnds(limits, *fcl, rng);
      for (const PlannerType type : o.planners) {
        const PlannerOptions options{.type = type,
                                     .resolution = o.resolution,
                                     .timeLimit = o.timeLimit,
                                     .simplifyTime = o.simplifyTime};
        for (const MethodPlan& each :
             planWithEachChecker(calibrated, gjk, fcl, limits, start, goal, options)) {
          const auto& [method, plan, exactShare] = each;
          table.add(joined({name, std::to_string(trial), plannerName(type), method},
                           joined(planCells(each, audit, o.resolution),
                                  {std::to_string(model->supportCount()), cell(counts.accuracy()),
                                   cell(counts.tpr())})));
        }
      }
    }
  }
  return table;
}

std::string planningReport(const Table& r, const PlanningOptions& o) {
  std::ostringstream md;
  md << "# Motion planning with moving obstacles (paper, Sec. IV-C, Figs. 13 and 14)\n\n"
     << featureSentence(o.features) << ' '
     << "Baxter's right arm; before each trial the boxes move 5 random-walk steps and the model "
        "makes 5 updates; start and goal are drawn collision-free with the shoulder yaw in "
        "opposite "
        "30% bands of its range. Every method plans the same query from scratch; Fastron and GJK "
        "plans are verified with FCL and invalid stretches replanned on FCL. Edges are checked "
        "every "
     << o.resolution << " rad; time limit " << o.timeLimit << " s per query; " << o.trials
     << " trial(s), seed " << o.seed << (o.quick ? ", quick mode" : "") << ". "
     << simplificationSentence(o.simplifyTime)
     << " Times are means ± std over solved queries; 'Final paths colliding' re-checks every "
        "final path with a separate FCL checker.\n\nThe paper (Figs. 13 and 14) found Fastron "
        "fastest with every planner even with verify and repair, up to 4 times faster than FCL "
        "with 7 joints and one box and up to 6 times faster initial plans with three boxes.\n";
  const auto planners = plannerNames(o.planners);
  for (const std::string& name : o.cases) {
    const Table::Filter fastron{{"case", name}, {"method", "Fastron"}, {"planner", planners[0]}};
    md << "\n## " << name << "\n\nModel (per trial, against FCL on fresh uniform configurations): "
       << "|S| " << meanStd(summarize(r.numbers("support", fastron)), 0) << ", accuracy "
       << meanStd(summarize(r.numbers("accuracy", fastron)), 3) << ", TPR "
       << meanStd(summarize(r.numbers("tpr", fastron)), 3) << ".\n\n"
       << planTable(r, {{"case", name}}, planners) << speedups(r, {{"case", name}}, planners);
  }
  return md.str();
}

Table runShelf(const ShelfOptions& o, const Progress& progress) {
  Table table{columnsWith({"trial", "planner", "method"}, {"support"}), {}};
  const Robot ur3 = loadRobot("ur3");
  // Joints within +-pi (the UR3 allows +-2 pi): one turn is all a reach into a shelf needs, and it
  // keeps the C-space one that an RRT explores in seconds.
  const JointLimits limits(ur3.limits().lower().cwiseMax(-std::numbers::pi),
                           ur3.limits().upper().cwiseMin(std::numbers::pi));
  const Scene scene = loadScene(dataDirectory() / "scenes" / "ur3_shelf.yaml");
  auto fcl = std::make_shared<FclChecker>(ur3, scene);
  auto gjk = std::make_shared<GjkChecker>(ur3, scene);
  const FclChecker audit(ur3, scene);
  ProxyCollisionDetector proxy(fcl, robotFeatures(ur3, o.features, limits),
                               experimentProxyParams(o.features, 10, 100, o.seed));
  if (progress) progress("shelf: training the model");
  proxy.initialize(o.quick ? 2000 : 8000);
  for (int update = 0; update < (o.quick ? 2 : 5); ++update) proxy.step();
  const CalibratedModel calibrated = proxy.calibratedModel();
  const auto& model = calibrated.model;

  // The end effector inside the shelf, above the lower board (start) or the upper one (goal),
  // reached through the open side: the wrist stays in front of the shelf, as a reach to pick or
  // place would (configurations threaded deeper in are pockets no planner gets out of in time).
  const int ee = ur3.linkIndex("ee_link");
  const int wrist = ur3.linkIndex("wrist_1_link");
  KinematicsData data = makeKinematicsData(ur3);
  Rng rng(o.seed);
  // Both checks in one predicate: the draws are those of drawing in the shelf, then rejecting
  // a colliding one.
  const auto inShelf = [&](double zLow, double zHigh) {
    return [&, zLow, zHigh](const Eigen::VectorXd& q) {
      forwardKinematics(ur3, q.data(), data, scene.robotBase);
      const Eigen::Vector3d p = data.linkPoses[static_cast<std::size_t>(ee)].translation();
      const Eigen::Vector3d w = data.linkPoses[static_cast<std::size_t>(wrist)].translation();
      return p.x() > 0.28 && p.x() < 0.44 && std::abs(p.y()) < 0.17 && p.z() > zLow &&
             p.z() < zHigh && w.x() < 0.24 && freeUnder(*fcl, q);
    };
  };
  const std::size_t trials = o.trials;
  for (std::size_t trial = 0; trial < trials; ++trial) {
    if (progress) progress("shelf: " + progressLine("query", trial, trials));
    const Eigen::VectorXd start =
        sampleReaching(inShelf(0.14, 0.26), limits, rng, "the lower shelf, collision-free");
    const Eigen::VectorXd goal =
        sampleReaching(inShelf(0.34, 0.46), limits, rng, "the higher shelf, collision-free");
    const PlannerOptions options{.type = PlannerType::Rrt,
                                 .resolution = o.resolution,
                                 .timeLimit = o.timeLimit,
                                 .simplifyTime = o.simplifyTime};
    for (const MethodPlan& each :
         planWithEachChecker(calibrated, gjk, fcl, limits, start, goal, options)) {
      const auto& [method, plan, exactShare] = each;
      table.add(joined(
          {std::to_string(trial), "RRT", method},
          joined(planCells(each, audit, o.resolution), {std::to_string(model->supportCount())})));
    }
  }
  return table;
}

std::string shelfReport(const Table& r, const ShelfOptions& o) {
  std::ostringstream md;
  md << "# UR3 shelf (paper, Sec. V-A)\n\n"
     << featureSentence(o.features)
     << " The UR3 reaches from the lower shelf to the higher one "
        "(start and goal drawn with the end effector inside the shelf, collision-free); RRT with "
        "Fastron (verified and repaired with FCL), GJK (verified and repaired) and FCL. Edges "
        "checked every "
     << o.resolution << " rad, time limit " << o.timeLimit << " s, seed " << o.seed
     << (o.quick ? ", quick mode" : "") << ". " << simplificationSentence(o.simplifyTime)
     << "\n\nThe paper (MATLAB): RRT with GJK 334.7 ms, with Fastron 119.7 ms including verify "
        "and repair (2.8 times faster).\n\n"
     << planTable(r, {}, {"RRT"}) << speedups(r, {}, {"RRT"});
  return md.str();
}

Table runSurgical(const SurgicalOptions& o, const Progress& progress) {
  Table table{columnsWith({"tick", "planner", "method"}, {"support", "model_updates"}), {}};
  const Robot psm = loadRobot("psm");
  const JointLimits limits = psm.limits();
  Scene scene = loadScene(dataDirectory() / "scenes" / "psm_surgical.yaml");
  auto fcl = std::make_shared<FclChecker>(psm, scene);
  auto gjk = std::make_shared<GjkChecker>(psm, scene);
  FclChecker audit(psm, scene);
  // The model learns a padded PSM3, so it stays conservative while the instruments move on
  // between its updates (paper, Sec. V-B).
  auto padded = std::make_shared<FclChecker>(psm, scene, CheckerOptions{.padding = o.padding});
  ProxyParams params = experimentProxyParams(o.features, 10, 100, o.seed);
  params.train.maxIterations = TrainParams{}.maxIterations;
  params.train.maxSupportPoints = TrainParams{}.maxSupportPoints;
  params.activeLearning.maxSamples = 300;
  params.seed = o.seed;
  params.labelThreads = 1;              // the other core plans
  std::atomic<std::size_t> updates{0};  // before the proxy: its thread counts here until joined
  ProxyCollisionDetector proxy(padded, robotFeatures(psm, o.features), params);
  if (progress) progress("surgical: training the model");
  proxy.initialize(o.quick ? 1000 : 3000);

  // Home: the instrument withdrawn; target: its tip between the two instruments, above the tissue.
  const int tip = psm.linkIndex("tool_wrist_link");
  KinematicsData data = makeKinematicsData(psm);
  Rng rng(o.seed);
  const Eigen::Vector3d targetPoint(-0.12, 0.0, 0.34);
  const Eigen::VectorXd home = sampleFree(
      *fcl,
      [&] {
        Eigen::VectorXd q = uniformIn(limits, rng);
        q[2] = 0.02;  // insertion
        return q;
      },
      "home configuration");
  const Eigen::VectorXd target = sampleReaching(
      [&](const Eigen::VectorXd& q) {
        forwardKinematics(psm, q.data(), data, scene.robotBase);
        return (data.linkPoses[static_cast<std::size_t>(tip)].translation() - targetPoint).norm() <
                   0.015 &&
               freeUnder(*fcl, q);
      },
      limits, rng, "the target point, collision-free");

  proxy.startBackground([&](const StepReport&) { updates.fetch_add(1); });
  Eigen::VectorXd current = home;
  bool towardTarget = true;
  const std::size_t ticks = o.quick ? 20 : o.ticks;
  const double stepLength = 0.05;  // joint units PSM3 moves along its plan per tick
  const PlannerOptions options{.type = PlannerType::Rrt,
                               .resolution = o.resolution,
                               .timeLimit = o.timeLimit,
                               .simplifyTime = o.simplifyTime};
  for (std::size_t tick = 0; tick < ticks; ++tick) {
    if (progress && tick % 20 == 0) progress("surgical: " + progressLine("tick", tick, ticks));
    scene.step();
    fcl->setScene(scene);
    gjk->setScene(scene);
    padded->setScene(scene);
    audit.setScene(scene);
    const Eigen::VectorXd goal = towardTarget ? target : home;
    if (!freeUnder(*fcl, current) || !freeUnder(*fcl, goal)) continue;  // blocked
    const CalibratedModel calibrated = proxy.calibratedModel();
    const auto& model = calibrated.model;
    const auto plans = planWithEachChecker(calibrated, gjk, fcl, limits, current, goal, options);
    for (const MethodPlan& each : plans) {
      const auto& [method, plan, exactShare] = each;
      table.add(
          joined({std::to_string(tick), "RRT", method},
                 joined(planCells(each, audit, o.resolution),
                        {std::to_string(model->supportCount()), std::to_string(updates.load())})));
    }
    // PSM3 follows the Fastron plan for one tick; at the goal it turns back.
    const VerifiedPlan& followed = plans.front().plan;
    if (!followed.solved()) continue;
    double left = stepLength;
    for (std::size_t k = 1; k < followed.path.size() && left > 0; ++k) {
      const Eigen::VectorXd delta = followed.path[k] - current;
      const double length = delta.norm();
      if (length <= left) {
        current = followed.path[k];
        left -= length;
      } else {
        current += delta * (left / length);
        left = 0;
      }
    }
    if ((current - goal).norm() < 1e-9) towardTarget = !towardTarget;
  }
  proxy.stopBackground();
  return table;
}

std::string surgicalReport(const Table& r, const SurgicalOptions& o) {
  std::ostringstream md;
  md << "# Autonomous surgical assistant (paper, Sec. V-B)\n\n"
     << featureSentence(o.features)
     << " PSM3 (yaw, pitch, insertion) "
        "moves between home and a target between the instruments of PSM1 and PSM2, which follow "
        "circles; at every tick each method plans an RRT from scratch from PSM3's current "
        "configuration, and PSM3 follows the Fastron plan. The model (of a PSM3 padded by "
     << o.padding
     << " m) updates in the background all along. Ticks where the instruments block PSM3 or its "
        "goal are skipped, as in the paper. Edges checked every "
     << o.resolution << " joint units; seed " << o.seed << (o.quick ? ", quick mode" : "") << ". "
     << simplificationSentence(o.simplifyTime)
     << "\n\nThe paper (MATLAB): 56 Hz replanning with Fastron, 10 Hz with GJK.\n\n"
     << "| Method | Replanning rate | Success | Mean total time |\n|---|---|---|---|\n";
  for (const std::string& method : r.distinct("method")) {
    const Summary total = summarize(r.numbers("total_s", {{"method", method}, {"solved", "1"}}));
    const Summary success = summarize(r.numbers("solved", {{"method", method}}));
    char line[160];
    std::snprintf(line, sizeof line, "| %s | %.1f Hz | %.2f | %s |\n", method.c_str(),
                  total.count ? 1.0 / total.mean : std::nan(""), success.mean,
                  durationMeanStd(total).c_str());
    md << line;
  }
  md << "\nThe rate is 1 / (mean time of plan + verify + repair) over solved ticks.\n\n"
     << planTable(r, {}, {"RRT"});
  return md.str();
}

namespace {

struct Problem {
  std::string id;
  std::filesystem::path scene, request;
};

/// The sceneNNNN.yaml files of `folder` that have a requestNNNN.yaml beside them, in order.
std::vector<Problem> problemsIn(const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder)) {
    throw FileError(folder.string() + ": not a folder of sceneNNNN.yaml / requestNNNN.yaml files");
  }
  std::vector<Problem> problems;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("scene") || entry.path().extension() != ".yaml") continue;
    const std::string id = name.substr(5, name.size() - 10);
    const auto request = folder / ("request" + id + ".yaml");
    if (std::filesystem::exists(request)) problems.push_back({id, entry.path(), request});
  }
  std::sort(problems.begin(), problems.end(),
            [](const Problem& a, const Problem& b) { return a.id < b.id; });
  if (problems.empty()) {
    throw FileError(folder.string() + ": no sceneNNNN.yaml with a matching requestNNNN.yaml");
  }
  return problems;
}

/// When the goal touches obstacles with the hand only (a grasp), allows those hand-object pairs
/// in the scene and returns a note naming them; returns a note saying why otherwise.
std::string allowGrasp(const Robot& robot, Scene& scene, const Eigen::VectorXd& goal) {
  const auto span = std::span<const double>(goal.data(), static_cast<std::size_t>(goal.size()));
  std::string note;
  for (int round = 0; round < 4; ++round) {
    const auto contact = FclChecker(robot, scene).firstContact(span);
    if (!contact) return note;
    const bool hand = contact->robotLink.find("hand") != std::string::npos ||
                      contact->robotLink.find("finger") != std::string::npos;
    if (contact->selfCollision || !hand) {
      return note + (note.empty() ? "" : "; ") + "goal collides: " + contact->robotLink +
             " touches " + contact->other;
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

}  // namespace

Table runMotionBench(const MotionBenchOptions& o, const Progress& progress) {
  Table table{columnsWith({"problem", "planner", "method", "note"}, {"support", "train_s"}), {}};
  std::vector<Problem> problems = problemsIn(o.problems);
  if (o.quick && problems.size() > 2) problems.resize(2);
  Robot robot = loadRobot(o.robot, UrdfOptions{.searchPaths = o.packagePaths}, o.srdf);
  const JointLimits limits = robot.limits();
  const FeatureMap features = robotFeatures(robot, o.features);
  const CheckerOptions checking{.selfCollision = o.selfCollision};
  for (std::size_t p = 0; p < problems.size(); ++p) {
    const Problem& problem = problems[p];
    if (progress)
      progress("motion-bench: " + progressLine("problem", p, problems.size()) + " (" +
               problem.scene.filename().string() + ")");
    Scene scene = loadScene(problem.scene);
    const PlanRequest request = loadMoveItRequest(problem.request);
    const auto toVector = [](const std::vector<double>& v) {
      return Eigen::VectorXd(
          Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
    };
    const Eigen::VectorXd start =
        toVector(actuatedConfiguration(robot, request.start, problem.request.string() + ": start"));
    const Eigen::VectorXd goal =
        toVector(actuatedConfiguration(robot, request.goal, problem.request.string() + ": goal"));
    const std::string note = allowGrasp(robot, scene, goal);
    auto fcl = std::make_shared<FclChecker>(robot, scene, checking);
    const FclChecker audit(robot, scene, checking);

    ProxyCollisionDetector proxy(fcl, features,
                                 experimentProxyParams(o.features, 5, 500, o.seed + p));
    const auto began = std::chrono::steady_clock::now();
    proxy.initialize(o.quick ? 1500 : o.trainingPoints);
    for (std::size_t u = 0; u < (o.quick ? 1 : o.updates); ++u) proxy.step();
    const double trainSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    const CalibratedModel calibrated = proxy.calibratedModel();
    const auto& model = calibrated.model;

    const PlannerOptions options{.type = PlannerType::RrtConnect,
                                 .resolution = o.resolution,
                                 .timeLimit = o.timeLimit,
                                 .simplifyTime = o.simplifyTime};
    for (const MethodPlan& each :
         planWithEachChecker(calibrated, nullptr, fcl, limits, start, goal, options)) {
      const auto& [method, plan, exactShare] = each;
      table.add(joined({problem.id, "RRTConnect", method, note},
                       joined(planCells(each, audit, o.resolution),
                              {std::to_string(model->supportCount()), cell(trainSeconds)})));
    }
  }
  return table;
}

std::string motionBenchReport(const Table& r, const MotionBenchOptions& o) {
  std::ostringstream md;
  md << "# MoveIt benchmark problems (" << o.problems.string() << ")\n\n"
     << featureSentence(o.features) << " Robot " << o.robot
     << (o.srdf.empty() ? "" : " with the disabled collisions of " + o.srdf.string())
     << (o.selfCollision ? ", self-collision checked by FCL" : ", self-collision not checked")
     << "; for each problem Fastron is trained on the scene ("
     << (o.quick ? 1500 : o.trainingPoints) << " samples, then " << (o.quick ? 1 : o.updates)
     << " active-learning updates) and RRT-Connect plans with Fastron (verified and repaired with "
        "FCL) and with FCL. Edges checked every "
     << o.resolution << " rad, time limit " << o.timeLimit << " s, seed " << o.seed
     << (o.quick ? ", quick mode" : "") << ". " << simplificationSentence(o.simplifyTime) << "\n\n"
     << "| Problem | Method | Status | Plan | Verify | Repair | Total | Path length | Collides "
        "(FCL) | Training | Note |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  const std::size_t status = r.index("status"), plan = r.index("plan_s"),
                    verify = r.index("verify_s"), repair = r.index("repair_s"),
                    total = r.index("total_s"), length = r.index("path_length"),
                    collides = r.index("collides_fcl"), train = r.index("train_s"),
                    note = r.index("note");
  const auto ms = [](const std::string& text) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f ms", std::stod(text) * 1e3);
    return std::string(buffer);
  };
  for (const auto& row : r.rows) {
    const bool fastron = row[r.index("method")] == "Fastron";
    md << "| " << row[r.index("problem")] << " | " << row[r.index("method")] << " | " << row[status]
       << " | " << ms(row[plan]) << " | " << ms(row[verify]) << " | " << ms(row[repair]) << " | "
       << ms(row[total]) << " | " << row[length].substr(0, 5) << " | " << row[collides] << " | "
       << (fastron ? ms(row[train]) : "—") << " | " << row[note] << " |\n";
  }
  md << "\n## Summary\n\n" << planTable(r, {}, {"RRTConnect"}) << speedups(r, {}, {"RRTConnect"});
  return md.str();
}

DemoResults runDemo(const DemoOptions& o, const Progress& progress) {
  const auto c = caseFor("7dof-3boxes");
  const Robot robot = baxterWithJoints(c.joints);
  const JointLimits limits = robot.limits();
  Scene scene = sceneForTrial(c.scene, o.seed);
  auto fcl = std::make_shared<FclChecker>(robot, scene);
  auto gjk = std::make_shared<GjkChecker>(robot, scene);
  FclChecker audit(robot, scene);
  ProxyParams params = proxyParams(c, o.seed, o.features);
  params.labelThreads = 1;  // the other core plans
  params.band = o.band;
  // Before the proxy: its thread updates these until it is joined.
  std::mutex updateMutex;
  std::size_t updates = 0;
  double updateSeconds = 0;
  ProxyCollisionDetector proxy(fcl, robotFeatures(robot, o.features), params);
  if (progress)
    progress("training the first model on " + std::to_string(o.initialPoints) +
             " FCL-labelled samples");
  proxy.initialize(o.initialPoints);

  DemoResults results;
  results.ticks = Table{
      columnsWith({"tick", "planner", "method"}, {"support", "accuracy", "tpr", "tnr", "updates"}),
      {}};
  // One update per tick: the boxes move once per tick, and updates on an unchanged world would
  // only grow the support set (and the query time).
  proxy.startBackground(
      [&](const StepReport& report) {
        const std::lock_guard lock(updateMutex);
        ++updates;
        updateSeconds += seconds(report.total);
      },
      std::chrono::duration_cast<std::chrono::nanoseconds>(
          std::chrono::duration<double>(o.tickSeconds)));
  Rng rng(o.seed);
  const auto began = std::chrono::steady_clock::now();
  for (std::size_t tick = 1; tick <= o.ticks; ++tick) {
    // Obstacles move at the pace of sensing, not of planning, so the model can follow them.
    std::this_thread::sleep_until(
        began + std::chrono::duration<double>(static_cast<double>(tick - 1) * o.tickSeconds));
    scene.step();
    fcl->setScene(scene);
    gjk->setScene(scene);
    audit.setScene(scene);
    const CalibratedModel calibrated = proxy.calibratedModel();
    const auto& model = calibrated.model;
    results.test.points = uniformConfigurations(limits, o.testPoints, rng);
    results.test.labels = labelConfigurations(audit, results.test.points, 1);
    const ConfusionCounts counts = evaluate(*model, results.test.points, results.test.labels);
    const auto [start, goal] = oppositeEnds(limits, *fcl, rng);
    const PlannerOptions options{.type = PlannerType::RrtConnect,
                                 .resolution = o.resolution,
                                 .timeLimit = o.timeLimit,
                                 .simplifyTime = o.simplifyTime};
    std::size_t updatesSoFar = 0;
    {
      const std::lock_guard lock(updateMutex);
      updatesSoFar = updates;
    }
    std::string line = "tick " + std::to_string(tick) + "/" + std::to_string(o.ticks) + ": |S| " +
                       std::to_string(model->supportCount()) + ", accuracy " +
                       cell(counts.accuracy()).substr(0, 5) + ", plans";
    for (const MethodPlan& each :
         planWithEachChecker(calibrated, gjk, fcl, limits, start, goal, options)) {
      const auto& [method, plan, exactShare] = each;
      if (method == "Fastron" && o.learnFromVerification) {
        proxy.addObservations(answersMissedBy(*model, plan.exactAnswers));
      }
      results.ticks.add(
          joined({std::to_string(tick), "RRTConnect", method},
                 joined(planCells(each, audit, o.resolution),
                        {std::to_string(model->supportCount()), cell(counts.accuracy()),
                         cell(counts.tpr()), cell(counts.tnr()), std::to_string(updatesSoFar)})));
      char part[64];
      std::snprintf(part, sizeof part, " %s %.1f ms%s", method.c_str(),
                    seconds(plan.totalTime()) * 1e3, plan.solved() ? "" : " (failed)");
      line += part;
    }
    if (progress && (tick % 10 == 0 || tick == 1)) progress(line);
  }
  proxy.stopBackground();
  results.elapsedSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  results.updates = updates;
  results.meanUpdateSeconds = updates ? updateSeconds / static_cast<double>(updates) : std::nan("");
  results.model = proxy.model();
  const Model& model = *results.model;
  results.fastronQuerySeconds = meanSecondsPerCall(
      results.test.points, [&](const double* q) { return model.inCollision(q); }, 0.05);
  results.gjkQuerySeconds = meanSecondsPerCheck(results.test.points, *gjk, 0.05);
  results.fclQuerySeconds = meanSecondsPerCheck(results.test.points, *fcl, 0.05);
  return results;
}

std::string demoReport(const DemoResults& r, const DemoOptions& o) {
  const Table& t = r.ticks;
  std::ostringstream md;
  char line[256];
  md << "# Fastron demo: Baxter's 7-joint arm among three moving boxes\n\n"
     << featureSentence(o.features) << ' '
     << "The model updates on a background thread from FCL labels (500 active-learning points per "
        "update); at each of "
     << o.ticks
     << " ticks the boxes move and RRT-Connect plans a fresh query (start and goal on opposite "
        "sides of the workspace) with each checker. Fastron and GJK plans are verified with FCL "
        "and invalid stretches replanned; edges are checked every "
     << o.resolution << " rad; seed " << o.seed << ". " << simplificationSentence(o.simplifyTime)
     << (o.learnFromVerification
             ? " The exact answers of a Fastron plan's verification and repair that the model got "
               "wrong are fed to its next update (learning from verification)."
             : " Verification answers are not fed back to the model.")
     << "\n\n## Model\n\n";
  std::snprintf(line, sizeof line,
                "- %zu background updates in %.1f s: %.1f updates/s, %.1f ms each (labelling + "
                "training)\n",
                r.updates, r.elapsedSeconds, static_cast<double>(r.updates) / r.elapsedSeconds,
                r.meanUpdateSeconds * 1e3);
  md << line;
  md << "- support points: " << meanStd(summarize(t.numbers("support", {{"method", "FCL"}})), 0)
     << "; against FCL on " << o.testPoints << " fresh configurations per tick: accuracy "
     << meanStd(summarize(t.numbers("accuracy", {{"method", "FCL"}})), 3) << ", TPR "
     << meanStd(summarize(t.numbers("tpr", {{"method", "FCL"}})), 3) << ", TNR "
     << meanStd(summarize(t.numbers("tnr", {{"method", "FCL"}})), 3) << "\n";
  std::snprintf(
      line, sizeof line, "- query time: Fastron %s, FK+GJK %s, FK+FCL %s (FCL / Fastron: %.1fx)\n",
      durationText(r.fastronQuerySeconds).c_str(), durationText(r.gjkQuerySeconds).c_str(),
      durationText(r.fclQuerySeconds).c_str(), r.fclQuerySeconds / r.fastronQuerySeconds);
  md << line << "\n## Planning (RRT-Connect)\n\n"
     << planTable(t, {}, {"RRTConnect"}) << speedups(t, {}, {"RRTConnect"});
  return md.str();
}

}  // namespace fastron
