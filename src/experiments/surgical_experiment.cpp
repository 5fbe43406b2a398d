#include "fastron/experiments/surgical_experiment.h"
#include "fastron/pipeline/presets.h"

#include <atomic>
#include <sstream>
#include <thread>

#include "fastron/experiments/report_text.h"
#include "fastron/experiments/statistics.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/geometry/scene_file.h"
#include "plan_rows.h"

namespace fastron::experiments {

namespace {

/// PSM3's two ends. Home: the instrument withdrawn; target: its tip between the two instruments,
/// above the tissue. Both free in `scene` under `fcl`.
std::pair<Eigen::VectorXd, Eigen::VectorXd> homeAndTarget(const Robot& psm, const Scene& scene,
                                                          const CollisionChecker& fcl,
                                                          std::uint64_t seed) {
  const JointLimits limits = psm.limits();
  const int tip = psm.linkIndex("tool_wrist_link");
  KinematicsData data = makeKinematicsData(psm);
  Rng rng(seed);
  const Eigen::Vector3d targetPoint(-0.12, 0.0, 0.34);
  const Eigen::VectorXd home = sampleFree(
      fcl,
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
               freeUnder(fcl, q);
      },
      limits, rng, "the target point, collision-free");
  return {home, target};
}

/// Moves `current` along `path` (which starts at it) by `stepLength` joint units, or to its end.
void followForOneTick(const JointPath& path, Eigen::VectorXd& current, double stepLength) {
  double left = stepLength;
  for (std::size_t k = 1; k < path.size() && left > 0; ++k) {
    const Eigen::VectorXd delta = path[k] - current;
    const double length = delta.norm();
    if (length <= left) {
      current = path[k];
      left -= length;
    } else {
      current += delta * (left / length);
      left = 0;
    }
  }
}

}  // namespace

PlanRows runSurgical(const SurgicalOptions& o, const Progress& progress) {
  PlanRows results;
  const Robot psm = loadRobot("psm");
  const JointLimits limits = psm.limits();
  Scene scene = loadScene(dataDirectory() / "scenes" / "psm_surgical.yaml");
  auto fcl = makeSceneChecker("fcl", psm, scene);
  auto gjk = makeSceneChecker("gjk", psm, scene);
  const auto audit = makeSceneChecker("fcl", psm, scene);
  // The model learns a padded PSM3, so it stays conservative while the instruments move on
  // between its updates (paper, Sec. V-B).
  auto padded = makeSceneChecker("fcl", psm, scene, CheckerOptions{.padding = o.padding});
  ProxyParams params = pipeline::robotProxyParams(o.features, 10, 100, o.seed);
  params.train.maxIterations = TrainParams{}.maxIterations;
  params.train.maxSupportPoints = TrainParams{}.maxSupportPoints;
  params.activeLearning.maxSamples = 300;
  params.seed = o.seed;
  params.labelThreads = 1;              // the other core plans
  std::atomic<std::size_t> updates{0};  // before the proxy: its thread counts here until joined
  ProxyCollisionDetector proxy(padded, robotFeatures(psm, o.features), params);
  if (progress) progress("surgical: training the model");
  proxy.initialize(o.quick ? 1000 : 3000);

  const auto [home, target] = homeAndTarget(psm, scene, *fcl, o.seed);
  proxy.startBackground([&](const StepReport&) { updates.fetch_add(1); });
  Eigen::VectorXd current = home;
  bool towardTarget = true;
  const std::size_t ticks = o.quick ? 20 : o.ticks;
  const double stepLength = 0.05;  // joint units PSM3 moves along its plan per tick
  const PlannerOptions options = plannerOptions(o, PlannerType::Rrt);
  for (std::size_t tick = 0; tick < ticks; ++tick) {
    if (progress && tick % 20 == 0) progress("surgical: " + progressLine("tick", tick, ticks));
    scene.step();
    fcl->setScene(scene);
    gjk->setScene(scene);
    padded->setScene(scene);
    audit->setScene(scene);
    const Eigen::VectorXd goal = towardTarget ? target : home;
    if (!freeUnder(*fcl, current) || !freeUnder(*fcl, goal)) continue;  // blocked
    const CalibratedModel calibrated = proxy.calibratedModel();
    const auto& model = calibrated.model;
    const auto plans =
        planWithEachChecker(calibrated, gjk, fcl, limits, current, goal, options, o.seed, tick);
    for (const MethodPlan& each : plans) {
      results.rows.push_back({{{"tick", std::to_string(tick)}},
                              "RRT",
                              each.method,
                              outcomeOf(each, *audit, o.resolution),
                              {{"support", static_cast<double>(model->supportCount())},
                               {"model_updates", static_cast<double>(updates.load())}}});
    }
    // PSM3 follows the Fastron plan for one tick; at the goal it turns back.
    const VerifiedPlan& followed = plans.front().plan;
    if (!followed.solved()) continue;
    followForOneTick(followed.path, current, stepLength);
    if ((current - goal).norm() < 1e-9) towardTarget = !towardTarget;
  }
  proxy.stopBackground();
  return results;
}

std::string surgicalReport(const PlanRows& r, const SurgicalOptions& o) {
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
     << edgeSteps(o, "joint units") << "; seed " << o.seed << (o.quick ? ", quick mode" : "")
     << ". " << simplificationSentence(o.simplifyTime, o.simplification)
     << "\n\nThe paper (MATLAB): 56 Hz replanning with Fastron, 10 Hz with GJK.\n\n"
     << "| Method | Replanning rate | Success | Mean total time |\n|---|---|---|---|\n";
  for (const std::string& method : experiments::methodsOf(r)) {
    std::vector<double> totals, solved;
    for (const PlanRow& row : r.rows) {
      if (row.method != method) continue;
      solved.push_back(row.outcome.solved ? 1.0 : 0.0);
      if (row.outcome.solved) totals.push_back(row.outcome.totalSeconds);
    }
    const Summary total = summarize(totals);
    const Summary success = summarize(solved);
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

}  // namespace fastron::experiments
