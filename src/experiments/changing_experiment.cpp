#include "fastron/experiments/changing_experiment.h"
#include "fastron/pipeline/presets.h"

#include <map>
#include <sstream>

#include "baxter_cases.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/support_reduction.h"
#include "fastron/experiments/statistics.h"
#include "fastron/experiments/timing.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/proxy/labelling.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron::experiments {

namespace {

/// The models' settings of a case: the options' kernel, bias and active learning over the case's
/// own. The paper's pipeline has no uncertainty band: its update times are compared without the
/// calibration points (the planning experiments keep them for the Hybrid method).
ProxyParams changingParams(const Case& c, std::uint64_t seed, const ChangingOptions& o) {
  ProxyParams params = pipeline::withoutBand(proxyParams(c, seed, o.features));
  if (o.gamma > 0) params.train.kernel.gamma = o.gamma;
  if (o.beta > 0) params.train.beta = o.beta;
  if (o.kernelBlock) params.train.kernel.block = *o.kernelBlock;
  if (o.wholeShare) params.train.kernel.wholeShare = *o.wholeShare;
  params.activeLearning.variance = o.variance;
  if (o.activeSamples > 0) params.activeLearning.maxSamples = o.activeSamples;
  if (o.warmStart) params = withWarmStart(params);
  return params;
}

/// One row: `at` (case, trial, step), the method, its scores and query time, and the parts of
/// the update it follows (NaN for an exact checker, which has none).
void addChangingRow(Table& table, const std::vector<std::string>& at, const std::string& method,
                    const ConfusionCounts& counts, double support, double query,
                    const StepReport* update) {
  const auto secondsOf = [&](auto part) {
    return update ? cell(std::chrono::duration<double>(part(*update)).count()) : cell(std::nan(""));
  };
  table.add({at[0], at[1], at[2], method, cell(counts.accuracy()), cell(counts.tpr()),
             cell(counts.tnr()), cell(support), cell(query),
             secondsOf([](const StepReport& r) { return r.total; }),
             secondsOf([](const StepReport& r) { return r.sampleTime; }),
             secondsOf([](const StepReport& r) { return r.labelTime; }),
             secondsOf([](const StepReport& r) { return r.update.elapsed; })});
}

/// The rows of the reductions of support_reduction.h (pruned, merged) of `model`, each timed as
/// part of the update `report` it follows; `modelRow(method, model, report)` adds a row.
template <class ModelRow>
void addReducedRows(const ChangingOptions& o, const Model& model, const StepReport& report,
                    const JointLimits& limits, Rng& reductionRng, const ModelRow& modelRow) {
  const auto reducedRow = [&](const std::string& method, auto reduce) {
    StepReport timed = report;
    const auto began = std::chrono::steady_clock::now();
    const std::shared_ptr<const Model> reduced = reduce(model);
    timed.total += std::chrono::steady_clock::now() - began;
    modelRow(method, *reduced, &timed);
  };
  if (o.pruneSamples > 0) {
    const Configurations heldOut = uniformConfigurations(limits, o.pruneSamples, reductionRng);
    reducedRow("Fastron (FCL, pruned)", [&](const Model& m) { return pruneSupport(m, heldOut); });
  }
  if (o.mergeRadius > 0) {
    reducedRow("Fastron (FCL, merged)",
               [&](const Model& m) { return mergeSupport(m, o.mergeRadius); });
  }
}

}  // namespace

Table runChanging(const ChangingOptions& o, const Progress& progress) {
  // update_s = sample_s + label_s + train_s (Algorithm 1) + the rest (the new points' features,
  // and their F from the weights a warm start keeps; publishing the model). No band here.
  Table table{{"case", "trial", "step", "method", "accuracy", "tpr", "tnr", "support", "query_s",
               "update_s", "sample_s", "label_s", "train_s"},
              {}};
  const std::size_t initial = o.quick ? 500 : 3000, tests = o.quick ? 300 : 2000;
  for (const std::string& name : o.cases) {
    const Case c = caseFor(name);
    const Robot robot = baxterWithJoints(c.joints);
    const JointLimits limits = robot.limits();
    const FeatureMap features = robotFeatures(robot, o.features);
    const bool jointRow = o.features != FeatureKind::JointScaling;
    for (std::size_t trial = 0; trial < o.trials; ++trial) {
      const std::uint64_t seed = o.seed * 1000 + trial;
      Scene scene = sceneForTrial(c.scene, seed);
      auto fcl = makeSceneChecker("fcl", robot, scene);
      auto gjk = makeSceneChecker("gjk", robot, scene);
      const ProxyParams params = changingParams(c, seed, o);
      ProxyCollisionDetector fromFcl(fcl, features, params), fromGjk(gjk, features, params),
          inJoints(fcl, limits,
                   pipeline::withoutBand(proxyParams(c, seed, FeatureKind::JointScaling)));
      fromFcl.initialize(initial);
      fromGjk.initialize(initial);
      if (jointRow) inJoints.initialize(initial);
      Rng rng(seed);
      Rng reductionRng(seed + 1);  // its own, so the other rows are those of a run without it
      for (std::size_t step = 1; step <= o.steps; ++step) {
        if (progress && (step == 1 || step % 10 == 0)) {
          progress("changing " + name + ", trial " + std::to_string(trial + 1) + "/" +
                   std::to_string(o.trials) + ", step " + std::to_string(step) + "/" +
                   std::to_string(o.steps));
        }
        scene.step();
        fcl->setScene(scene);
        gjk->setScene(scene);
        const StepReport rf = fromFcl.step(), rg = fromGjk.step();
        const StepReport rj = jointRow ? inJoints.step() : StepReport{};
        const Configurations test = uniformConfigurations(limits, tests, rng);
        const Labels truth = labelConfigurations(*fcl, test);
        const std::vector<std::string> at{name, std::to_string(trial), std::to_string(step)};
        const auto row = [&](const std::string& method, const ConfusionCounts& counts,
                             double support, double query, const StepReport* update) {
          addChangingRow(table, at, method, counts, support, query, update);
        };
        std::vector<std::tuple<const char*, const ProxyCollisionDetector*, const StepReport*>>
            proxies{{"Fastron (FCL)", &fromFcl, &rf}, {"Fastron (GJK)", &fromGjk, &rg}};
        if (jointRow) proxies.emplace_back("Fastron (FCL, joints)", &inJoints, &rj);
        const auto modelRow = [&](const std::string& method, const Model& model,
                                  const StepReport* report) {
          const Eigen::VectorXd scores = model.scoreBatch(test);
          row(method,
              confusionOf(truth,
                          [&](std::size_t i) { return scores[static_cast<Eigen::Index>(i)] > 0; }),
              static_cast<double>(model.supportCount()),
              meanSecondsPerCall(
                  test, [&](const double* q) { return model.inCollision(q); }, 0.01),
              report);
        };
        for (const auto& [method, proxy, report] : proxies) {
          modelRow(method, *proxy->model(), report);
        }
        addReducedRows(o, *fromFcl.model(), rf, limits, reductionRng, modelRow);
        const Labels gjkLabels = labelConfigurations(*gjk, test);
        row("FK+GJK", confusionOf(truth, [&](std::size_t i) { return gjkLabels[i] > 0; }),
            std::nan(""), meanSecondsPerCheck(test, *gjk, 0.01), nullptr);
        row("FK+FCL", confusionOf(truth, [&](std::size_t i) { return truth[i] > 0; }), std::nan(""),
            meanSecondsPerCheck(test, *fcl, 0.01), nullptr);
      }
    }
  }
  return table;
}

namespace {

// The paper's tables (Figs. 8 and 10): |S|, query time, update time.
const std::map<std::pair<std::string, std::string>, std::array<std::string, 3>> kPaperChanging{
    {{"4dof", "Fastron (FCL)"}, {"638.6 ± 139.4", "2.1 ± 0.5 µs", "42.0 ± 5.8 ms"}},
    {{"4dof", "Fastron (GJK)"}, {"558.1 ± 151.1", "1.9 ± 0.5 µs", "15.8 ± 3.8 ms"}},
    {{"4dof", "FK+GJK"}, {"—", "9.1 ± 0.2 µs", "—"}},
    {{"4dof", "FK+FCL"}, {"—", "29.2 ± 0.5 µs", "—"}},
    {{"6dof", "Fastron (FCL)"}, {"1060.5 ± 217.9", "4.1 ± 0.8 µs", "62.4 ± 10.4 ms"}},
    {{"6dof", "Fastron (GJK)"}, {"886.8 ± 215.5", "3.5 ± 0.9 µs", "24.2 ± 6.4 ms"}},
    {{"6dof", "FK+GJK"}, {"—", "9.5 ± 0.2 µs", "—"}},
    {{"6dof", "FK+FCL"}, {"—", "30.5 ± 0.5 µs", "—"}},
    {{"7dof", "Fastron (FCL)"}, {"1306.0 ± 291.7", "5.5 ± 1.2 µs", "74.7 ± 15.7 ms"}},
    {{"7dof", "Fastron (GJK)"}, {"1151.3 ± 283.9", "4.9 ± 1.2 µs", "32.6 ± 7.5 ms"}},
    {{"7dof", "FK+GJK"}, {"—", "9.6 ± 0.4 µs", "—"}},
    {{"7dof", "FK+FCL"}, {"—", "29.3 ± 0.5 µs", "—"}},
    {{"7dof-3boxes", "Fastron (FCL)"}, {"1637.5 ± 305.9", "6.7 ± 1.2 µs", "89.2 ± 17.4 ms"}},
    {{"7dof-3boxes", "Fastron (GJK)"}, {"1582.9 ± 321.1", "6.6 ± 1.4 µs", "56.3 ± 14.5 ms"}},
    {{"7dof-3boxes", "FK+GJK"}, {"—", "15.3 ± 1.6 µs", "—"}},
    {{"7dof-3boxes", "FK+FCL"}, {"—", "29.1 ± 0.8 µs", "—"}},
};

}  // namespace

std::string changingReport(const Table& r, const ChangingOptions& o) {
  std::ostringstream md;
  md << "# Changing environments (paper, Sec. IV-B, Figs. 8 to 11)\n\nBaxter's right arm, boxes on "
        "random walks of 1 to 4 cm "
     << "per step; " << o.trials << " trial(s) of " << o.steps << " updates per case, seed "
     << o.seed << (o.quick ? ", quick mode" : "") << ". Fastron's input: "
     << (o.features == FeatureKind::Kinematic
             ? "task-space features (world positions of the automatic control points, "
               "docs/algorithms.md); 'Fastron (FCL, joints)' is the paper's joint-space model "
               "beside them"
             : "joint values scaled to [-1, 1] (the paper's)")
     << (o.gamma > 0 ? ", gamma " + cell(o.gamma) : "")
     << (o.beta > 0 ? ", beta " + cell(o.beta) : "")
     << (o.variance > 0 ? ", active-learning variance " + cell(o.variance) : "")
     << (o.activeSamples > 0 ? ", A_max " + std::to_string(o.activeSamples) : "")
     << (o.warmStart ? ", updates from the last weights (warm start)" : "")
     << (o.kernelBlock ? ", kernel block " + std::to_string(*o.kernelBlock) : "")
     << (o.wholeShare ? ", whole-vector share " + cell(*o.wholeShare) : "")
     << (o.pruneSamples > 0 ? "; 'pruned': pruneSupport on " + std::to_string(o.pruneSamples) +
                                  " fresh uniform configurations per update"
                            : "")
     << (o.mergeRadius > 0 ? "; 'merged': mergeSupport with radius " + cell(o.mergeRadius) : "")
     << ". Accuracy, TPR and TNR against FCL on fresh configurations after every update; mean ± "
        "standard deviation over all "
     << "updates of all trials; the paper's values (C++, MoveIt's Baxter, 2018 hardware) beside "
        "ours.\n";
  for (const std::string& name : o.cases) {
    md << "\n## " << name
       << "\n\n| Method | |S| | Query time | Update time | Accuracy | TPR | TNR | paper |S| | "
          "paper query | paper update |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string method :
         {"Fastron (FCL)", "Fastron (FCL, pruned)", "Fastron (FCL, merged)", "Fastron (GJK)",
          "Fastron (FCL, joints)", "FK+GJK", "FK+FCL"}) {
      if (r.numbers("accuracy", {{"case", name}, {"method", method}}).empty()) continue;
      const auto paper = kPaperChanging.find(
          {name, method.starts_with("Fastron (FCL") ? std::string("Fastron (FCL)") : method});
      md << methodRow(r, method, {{"case", name}, {"method", method}}, "update_s",
                      paper == kPaperChanging.end() ? std::array<std::string, 3>{} : paper->second);
    }
    // Where an update's time goes, for the models that learn from FCL.
    md << '\n';
    for (const std::string method : {"Fastron (FCL)", "Fastron (FCL, joints)"}) {
      const Table::Filter where{{"case", name}, {"method", method}};
      if (r.numbers("update_s", where).empty()) continue;
      const auto mean = [&](const char* column) {
        return summarize(r.numbers(column, where)).mean;
      };
      const double total = mean("update_s"), sample = mean("sample_s"), label = mean("label_s"),
                   train = mean("train_s");
      md << method << ": an update of " << durationText(total) << " is sampling "
         << durationText(sample) << ", labelling " << durationText(label) << ", Algorithm 1 "
         << durationText(train) << " and " << durationText(total - sample - label - train)
         << " for the rest (the new points' features, and their F when an update keeps the "
            "weights; publishing the model).\n\n";
    }
  }
  return md.str();
}

Table runObstacleSweep(const SweepOptions& o, const Progress& progress) {
  Table table{{"obstacles", "trial", "method", "query_s", "support", "cobs_fraction"}, {}};
  const Robot robot = baxterWithJoints(7);
  const JointLimits limits = robot.limits();
  const Eigen::AlignedBox3d space(Eigen::Vector3d(0.25, -1.10, -0.30),
                                  Eigen::Vector3d(1.05, -0.15, 0.75));
  const Case c = caseFor("7dof");
  const FeatureMap features = robotFeatures(robot, o.features);
  for (const std::size_t count : o.obstacles) {
    for (std::size_t trial = 0; trial < o.trials; ++trial) {
      if (progress)
        progress("sweep: " + std::to_string(count) + " obstacles, trial " +
                 std::to_string(trial + 1) + "/" + std::to_string(o.trials));
      Rng rng(o.seed * 1000 + count * 10 + trial);
      Scene scene;
      std::uniform_real_distribution<double> u(0.0, 1.0);
      for (std::size_t k = 0; k < count; ++k) {
        const Eigen::Vector3d p =
            space.min() + space.sizes().cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
        scene.add({"box" + std::to_string(k), Box{Eigen::Vector3d::Constant(0.1)}, makePose(p),
                   std::nullopt});
      }
      auto fcl = makeSceneChecker("fcl", robot, scene);
      const auto gjk = makeSceneChecker("gjk", robot, scene);
      ProxyCollisionDetector proxy(fcl, features, proxyParams(c, rng(), o.features));
      proxy.initialize(o.quick ? 500 : 3000);
      for (int s = 0; s < (o.quick ? 2 : 10); ++s)
        proxy.step();  // active learning refines the static scene
      const auto model = proxy.model();
      const Configurations test = uniformConfigurations(limits, o.quick ? 300 : 2000, rng);
      const Labels truth = labelConfigurations(*fcl, test);
      const double cobs = static_cast<double>(std::count(truth.begin(), truth.end(), 1)) /
                          static_cast<double>(truth.size());
      auto row = [&](const std::string& method, double query, double support) {
        table.add({std::to_string(count), std::to_string(trial), method, cell(query), cell(support),
                   cell(cobs)});
      };
      row("Fastron",
          meanSecondsPerCall(
              test, [&](const double* q) { return model->inCollision(q); }, 0.02),
          static_cast<double>(model->supportCount()));
      row("FK+GJK", meanSecondsPerCheck(test, *gjk, 0.02), std::nan(""));
      row("FK+FCL", meanSecondsPerCheck(test, *fcl, 0.02), std::nan(""));
    }
  }
  return table;
}

std::string sweepReport(const Table& r, const SweepOptions& o) {
  std::ostringstream md;
  md << "# Query time against the number of obstacles (paper, Fig. 12)\n\nBaxter's 7-DOF right arm "
        "among 0.1 m boxes placed at "
     << "random in its reachable space, " << o.trials << " trial(s) per count, seed " << o.seed
     << (o.quick ? ", quick mode" : "")
     << ". Fastron trained on FCL labels (initial set plus active-learning updates), on "
     << (o.features == FeatureKind::Kinematic ? "task-space features" : "joint values") << ".\n\n"
     << "| obstacles | C-space in collision | Fastron |S| | Fastron | FK + GJK | FK + FCL "
        "|\n|---|---|---|---|---|---|\n";
  for (const std::string& count : r.distinct("obstacles")) {
    auto stat = [&](const std::string& method, const std::string& column) {
      return summarize(r.numbers(column, {{"obstacles", count}, {"method", method}}));
    };
    md << "| " << count << " | " << meanStd(stat("Fastron", "cobs_fraction"), 3) << " | "
       << meanStd(stat("Fastron", "support"), 0) << " | "
       << durationMeanStd(stat("Fastron", "query_s")) << " | "
       << durationMeanStd(stat("FK+GJK", "query_s")) << " | "
       << durationMeanStd(stat("FK+FCL", "query_s")) << " |\n";
  }
  return md.str();
}

}  // namespace fastron::experiments
