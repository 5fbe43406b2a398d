#include "fastron/experiments/planning_experiment.h"

#include <sstream>

#include "baxter_cases.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/metrics.h"
#include "fastron/experiments/report_text.h"
#include "fastron/experiments/statistics.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/proxy/labelling.h"
#include "plan_rows.h"

namespace fastron::experiments {

PlanRows runPlanning(const PlanningOptions& o, const Progress& progress) {
  PlanRows results;
  const std::size_t initial = o.quick ? 1000 : 3000;
  const std::size_t testPoints = o.quick ? 300 : 1000;
  for (const std::string& name : o.cases) {
    const auto c = caseFor(name);
    const Robot robot = baxterWithJoints(c.joints);
    const JointLimits limits = robot.limits();
    const std::uint64_t seed = o.seed * 1000 + c.joints;
    Scene scene = sceneForTrial(c.scene, seed);
    auto fcl = makeSceneChecker("fcl", robot, scene);
    auto gjk = makeSceneChecker("gjk", robot, scene);
    const auto audit = makeSceneChecker("fcl", robot, scene);
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
      audit->setScene(scene);
      for (int update = 0; update < 5; ++update) proxy.step();
      const CalibratedModel calibrated = proxy.calibratedModel();
      const auto& model = calibrated.model;
      // The model's accuracy beside its speed: fresh configurations, labelled by the audit FCL.
      const Configurations test = uniformConfigurations(limits, testPoints, rng);
      const ConfusionCounts counts = evaluate(*model, test, labelConfigurations(*audit, test, 1));
      const auto [start, goal] = oppositeEnds(limits, *fcl, rng);
      for (std::size_t k = 0; k < o.planners.size(); ++k) {
        const PlannerType type = o.planners[k];
        const PlannerOptions options = plannerOptions(o, type);
        for (const MethodPlan& each : planWithEachChecker(calibrated, gjk, fcl, limits, start, goal,
                                                          options, seed, trial + k)) {
          results.rows.push_back({{{"case", name}, {"trial", std::to_string(trial)}},
                                  plannerName(type),
                                  each.method,
                                  outcomeOf(each, *audit, o.resolution),
                                  {{"support", static_cast<double>(model->supportCount())},
                                   {"accuracy", counts.accuracy()},
                                   {"tpr", counts.tpr()}}});
        }
      }
    }
  }
  return results;
}

std::string planningReport(const PlanRows& r, const PlanningOptions& o) {
  std::ostringstream md;
  md << "# Motion planning with moving obstacles (paper, Sec. IV-C, Figs. 13 and 14)\n\n"
     << featureSentence(o.features) << ' '
     << "Baxter's right arm; before each trial the boxes move 5 random-walk steps and the model "
        "makes 5 updates; start and goal are drawn collision-free with the shoulder yaw in "
        "opposite "
        "30% bands of its range. Every method plans the same query from scratch; Fastron and GJK "
        "plans are verified with FCL and invalid stretches replanned on FCL. Edges are checked "
        "every "
     << edgeSteps(o, "rad") << "; time limit " << o.timeLimit << " s per query; " << o.trials
     << " trial(s), seed " << o.seed << (o.quick ? ", quick mode" : "") << ". "
     << simplificationSentence(o.simplifyTime, o.simplification)
     << " Times are means ± std over solved queries; 'Final paths colliding' re-checks every "
        "final path with a separate FCL checker.\n\nThe paper (Figs. 13 and 14) found Fastron "
        "fastest with every planner even with verify and repair, up to 4 times faster than FCL "
        "with 7 joints and one box and up to 6 times faster initial plans with three boxes.\n";
  const auto planners = plannerNames(o.planners);
  for (const std::string& name : o.cases) {
    const auto inCase = [&](const PlanRow& row) { return row.queryValue("case") == name; };
    // The model's figures, once per trial: from Fastron's rows of the first planner.
    std::vector<double> support, accuracy, tpr;
    for (const PlanRow& row : r.rows) {
      if (!inCase(row) || row.method != "Fastron" || row.planner != planners[0]) continue;
      support.push_back(row.figure("support"));
      accuracy.push_back(row.figure("accuracy"));
      tpr.push_back(row.figure("tpr"));
    }
    md << "\n## " << name << "\n\nModel (per trial, against FCL on fresh uniform configurations): "
       << "|S| " << meanStd(summarize(support), 0) << ", accuracy "
       << meanStd(summarize(accuracy), 3) << ", TPR " << meanStd(summarize(tpr), 3) << ".\n\n"
       << planTable(r, inCase, planners) << speedups(r, inCase, planners)
       << "\nWhere the time goes (medians over solved plans):\n\n"
       << timeBreakdown(r, inCase, planners);
  }
  return md.str();
}

}  // namespace fastron::experiments
