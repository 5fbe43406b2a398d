#include "fastron/experiments/shelf_experiment.h"
#include "fastron/pipeline/presets.h"

#include <numbers>
#include <sstream>

#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/geometry/scene_file.h"
#include "plan_rows.h"

namespace fastron::experiments {

PlanRows runShelf(const ShelfOptions& o, const Progress& progress) {
  PlanRows results;
  const Robot ur3 = loadRobot("ur3");
  // Joints within +-pi (the UR3 allows +-2 pi): one turn is all a reach into a shelf needs, and it
  // keeps the C-space one that an RRT explores in seconds.
  const JointLimits limits(ur3.limits().lower().cwiseMax(-std::numbers::pi),
                           ur3.limits().upper().cwiseMin(std::numbers::pi));
  const Scene scene = loadScene(dataDirectory() / "scenes" / "ur3_shelf.yaml");
  auto fcl = makeSceneChecker("fcl", ur3, scene);
  auto gjk = makeSceneChecker("gjk", ur3, scene);
  const auto audit = makeSceneChecker("fcl", ur3, scene);
  ProxyCollisionDetector proxy(
      fcl, robotFeatures(ur3, o.features, limits),
      pipeline::forStaticScene(pipeline::robotProxyParams(o.features, 10, 100, o.seed)));
  if (progress) progress("shelf: training the model");
  trainStatic(proxy, o.quick ? 2000 : 8000, o.quick ? 2 : 5);
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
    const PlannerOptions options = plannerOptions(o, PlannerType::Rrt);
    for (const MethodPlan& each :
         planWithEachChecker(calibrated, gjk, fcl, limits, start, goal, options, o.seed, trial)) {
      results.rows.push_back({{{"trial", std::to_string(trial)}},
                              "RRT",
                              each.method,
                              outcomeOf(each, *audit, o.resolution),
                              {{"support", static_cast<double>(model->supportCount())}}});
    }
  }
  return results;
}

std::string shelfReport(const PlanRows& r, const ShelfOptions& o) {
  std::ostringstream md;
  md << "# UR3 shelf (paper, Sec. V-A)\n\n"
     << featureSentence(o.features)
     << " The UR3 reaches from the lower shelf to the higher one "
        "(start and goal drawn with the end effector inside the shelf, collision-free); RRT with "
        "Fastron (verified and repaired with FCL), GJK (verified and repaired) and FCL. Edges "
        "checked every "
     << edgeSteps(o, "rad") << ", time limit " << o.timeLimit << " s, seed " << o.seed
     << (o.quick ? ", quick mode" : "") << ". "
     << simplificationSentence(o.simplifyTime, o.simplification)
     << "\n\nThe paper (MATLAB): RRT with GJK 334.7 ms, with Fastron 119.7 ms including verify "
        "and repair (2.8 times faster).\n\n"
     << planTable(r, {}, {"RRT"}) << speedups(r, {}, {"RRT"});
  return md.str();
}

}  // namespace fastron::experiments
