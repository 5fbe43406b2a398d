#include "fastron/experiments/demo_experiment.h"

#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <thread>
#include <utility>

#include "baxter_cases.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/metrics.h"
#include "fastron/experiments/report_text.h"
#include "fastron/experiments/statistics.h"
#include "fastron/experiments/timing.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/proxy/labelling.h"
#include "plan_rows.h"

namespace fastron::experiments {
namespace {

/// The demo's pipeline: the 7dof-3boxes case's, labelling on one core (the other plans).
ProxyParams demoProxyParams(const DemoOptions& o) {
  ProxyParams params = proxyParams(caseFor("7dof-3boxes"), o.seed, o.features);
  params.labelThreads = 1;
  params.band = o.band;
  if (o.wholeShare) params.train.kernel.wholeShare = *o.wholeShare;
  if (o.gamma) params.train.kernel.gamma = *o.gamma;
  if (o.beta) params.train.beta = *o.beta;
  params.pointField = true;  // models of point terms alone answer from their grids
  params.fieldAnswers = o.fieldAnswers;
  return params;
}

}  // namespace

namespace {

/// The background updates counted and timed, from the proxy's thread.
class UpdateTally {
 public:
  void add(const StepReport& report) {
    const std::lock_guard lock(mutex_);
    ++count_;
    seconds_ += inSeconds(report.total);
  }
  std::size_t count() const {
    const std::lock_guard lock(mutex_);
    return count_;
  }
  double meanSeconds() const {
    const std::lock_guard lock(mutex_);
    return count_ > 0 ? seconds_ / static_cast<double>(count_) : std::nan("");
  }

 private:
  mutable std::mutex mutex_;
  std::size_t count_ = 0;
  double seconds_ = 0;
};

/// `n` uniform configurations labelled by `exact` on the calling thread.
Dataset labelledUniform(const JointLimits& limits, std::size_t n, Rng& rng,
                        const CollisionChecker& exact) {
  Dataset data;
  data.points = uniformConfigurations(limits, n, rng);
  data.labels = labelConfigurations(exact, data.points, 1);
  return data;
}

/// A tick's figures beside each plan: the model's |S|, its scores, the updates so far.
std::vector<std::pair<std::string, double>> tickFigures(const Model& model,
                                                        const ConfusionCounts& counts,
                                                        std::size_t updates) {
  return {{"support", static_cast<double>(model.supportCount())},
          {"accuracy", counts.accuracy()},
          {"tpr", counts.tpr()},
          {"tnr", counts.tnr()},
          {"updates", static_cast<double>(updates)}};
}

/// " Fastron 1.2 ms" (or " FCL 48.0 ms (failed)") for the progress line.
std::string planSummary(const std::string& method, const VerifiedPlan& plan) {
  char part[64];
  std::snprintf(part, sizeof part, " %s %.1f ms%s", method.c_str(),
                inSeconds(plan.totalTime()) * 1e3, plan.solved() ? "" : " (failed)");
  return part;
}

/// The last model's query time and the exact checkers', on the test points kept.
void addQueryTimes(DemoResults& results, const CollisionChecker& gjk, const CollisionChecker& fcl) {
  const Model& model = *results.model;
  results.fastronQuerySeconds = meanSecondsPerCall(
      results.test.points, [&](const double* q) { return model.inCollision(q); }, 0.05);
  results.gjkQuerySeconds = meanSecondsPerCheck(results.test.points, gjk, 0.05);
  results.fclQuerySeconds = meanSecondsPerCheck(results.test.points, fcl, 0.05);
}

}  // namespace

DemoResults runDemo(const DemoOptions& o, const Progress& progress) {
  const auto c = caseFor("7dof-3boxes");
  const Robot robot = baxterWithJoints(c.joints);
  const JointLimits limits = robot.limits();
  Scene scene = sceneForTrial(c.scene, o.seed);
  auto fcl = makeSceneChecker("fcl", robot, scene);
  auto gjk = makeSceneChecker("gjk", robot, scene);
  const auto audit = makeSceneChecker("fcl", robot, scene);
  const ProxyParams params = demoProxyParams(o);
  UpdateTally tally;  // before the proxy: its thread updates it until joined
  const std::vector<ControlPoint> points = o.features == FeatureKind::Kinematic
                                               ? defaultControlPoints(robot, o.controlPoints)
                                               : std::vector<ControlPoint>{};
  ProxyCollisionDetector proxy(fcl, robotFeatures(robot, o.features, points), params);
  if (progress)
    progress("training the first model on " + std::to_string(o.initialPoints) +
             " FCL-labelled samples");
  proxy.initialize(o.initialPoints);

  DemoResults results;
  // One update per tick: the boxes move once per tick, and updates on an unchanged world would
  // only grow the support set (and the query time).
  proxy.startBackground([&](const StepReport& report) { tally.add(report); },
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
    audit->setScene(scene);
    const CalibratedModel calibrated = proxy.calibratedModel();
    const auto& model = calibrated.model;
    Dataset test = labelledUniform(limits, o.testPoints, rng, *audit);
    const ConfusionCounts counts = evaluate(*model, test.points, test.labels);
    // The boxes can block one side of the workspace for a while: then this tick plans nothing.
    const auto ends = tryOppositeEnds(limits, *fcl, rng, 20000);
    // Kept: the model and test points of the last tick with rows (of this tick while none has).
    if (ends || results.ticks.rows.empty()) {
      results.model = model;
      results.test = std::move(test);
    }
    if (!ends) {
      ++results.blockedTicks;
      if (progress) progress("tick " + std::to_string(tick) + ": no free start or goal, skipped");
      continue;
    }
    const auto& [start, goal] = *ends;
    const PlannerOptions options = plannerOptions(o, PlannerType::RrtConnect);
    const std::size_t updatesSoFar = tally.count();
    std::string line = "tick " + std::to_string(tick) + "/" + std::to_string(o.ticks) + ": |S| " +
                       std::to_string(model->supportCount()) + ", accuracy " +
                       cell(counts.accuracy()).substr(0, 5) + ", plans";
    for (const MethodPlan& each :
         planWithEachChecker(calibrated, gjk, fcl, limits, start, goal, options, o.seed, tick)) {
      const auto& [method, plan, exactShare] = each;
      if (method == "Fastron" && o.learnFromVerification) {
        proxy.addObservations(answersMissedBy(*model, plan.exactAnswers));
      }
      results.ticks.rows.push_back({{{"tick", std::to_string(tick)}},
                                    "RRTConnect",
                                    method,
                                    outcomeOf(each, *audit, o.resolution),
                                    tickFigures(*model, counts, updatesSoFar)});
      line += planSummary(method, plan);
    }
    if (progress && (tick % 10 == 0 || tick == 1)) progress(line);
  }
  proxy.stopBackground();
  results.elapsedSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  results.updates = tally.count();
  results.meanUpdateSeconds = tally.meanSeconds();
  addQueryTimes(results, *gjk, *fcl);
  return results;
}

std::string demoReport(const DemoResults& r, const DemoOptions& o) {
  const PlanRows& t = r.ticks;
  // The model's figures, once per tick: from FCL's rows.
  const auto modelFigure = [&](const char* name) {
    std::vector<double> values;
    for (const PlanRow& row : t.rows) {
      if (row.method == "FCL") values.push_back(row.figure(name));
    }
    return summarize(values);
  };
  const ProxyParams pipeline = demoProxyParams(o);
  std::ostringstream md;
  char line[256];
  md << "# Fastron demo: Baxter's 7-joint arm among three moving boxes\n\n"
     << featureSentence(o.features) << ' '
     << "The model updates on a background thread from FCL labels ("
     << pipeline.activeLearning.maxSamples << " active-learning points per update, "
     << (pipeline.activeLearning.exploitationShare < 1 ? "most of them uniform, " : "")
     << "Algorithm 1 " << (pipeline.coldStart ? "from zero weights" : "from the last weights")
     << "); at each of " << o.ticks
     << " ticks the boxes move and RRT-Connect plans a fresh query (start and goal on opposite "
        "sides of the workspace) with each checker. Fastron and GJK plans are verified with FCL "
        "and invalid stretches replanned; edges are checked every "
     << edgeSteps(o, "rad") << "; seed " << o.seed << ". "
     << simplificationSentence(o.simplifyTime, o.simplification)
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
  md << "- support points: " << meanStd(modelFigure("support"), 0) << "; against FCL on "
     << o.testPoints << " fresh configurations per tick: accuracy "
     << meanStd(modelFigure("accuracy"), 3) << ", TPR " << meanStd(modelFigure("tpr"), 3)
     << ", TNR " << meanStd(modelFigure("tnr"), 3) << "\n";
  std::snprintf(
      line, sizeof line, "- query time: Fastron %s, FK+GJK %s, FK+FCL %s (FCL / Fastron: %.1fx)\n",
      durationText(r.fastronQuerySeconds).c_str(), durationText(r.gjkQuerySeconds).c_str(),
      durationText(r.fclQuerySeconds).c_str(), r.fclQuerySeconds / r.fastronQuerySeconds);
  md << line;
  if (r.model) {
    md << "- kernel: " << toString(r.model->kernel().type) << ", gamma " << r.model->kernel().gamma
       << ", " << describeTerms(r.model->kernel(), r.model->featureDim());
    if (const PointField* field = r.model->pointField()) {
      md << "; answers from a point field of " << field->grids().size() << " grids of "
         << field->spacing() * 100 << " cm cells, answers " << toString(field->answers())
         << " (Fastron's query time above)";
    }
    if (const auto& kinematics = r.model->features().kinematics())
      md << "; features: the positions of " << kinematics->pointCount() << " control points";
    md << '\n';
  }
  md << "\n## Planning (RRT-Connect)\n\n";
  if (r.blockedTicks > 0) {
    md << r.blockedTicks << " of " << o.ticks
       << " ticks planned nothing: the boxes left no free start or goal on a side of the "
          "workspace.\n\n";
  }
  md << planTable(t, {}, {"RRTConnect"}) << speedups(t, {}, {"RRTConnect"})
     << "\nWhere the time goes (medians over solved plans):\n\n"
     << timeBreakdown(t, {}, {"RRTConnect"});
  return md.str();
}

}  // namespace fastron::experiments
