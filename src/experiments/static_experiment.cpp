#include "fastron/experiments/static_experiment.h"

#include <chrono>
#include <map>
#include <sstream>

#include "fastron/baselines/fastron_classifier.h"
#include "fastron/baselines/incremental_svm.h"
#include "fastron/baselines/libsvm_classifier.h"
#include "fastron/baselines/sparse_svm.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/experiments/random_scenes.h"
#include "fastron/experiments/statistics.h"
#include "fastron/experiments/timing.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/proxy/labelling.h"

namespace fastron::experiments {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The paper's settings per robot (Sec. IV-A), and the cubes' sizes relative to the reach.
struct Setup {
  std::string robot;
  std::size_t n;
  double gamma, reach, minSide, maxSide;
};

Setup setupFor(int dof, bool quick) {
  if (dof == 2) return {"rod2", quick ? 300u : 2000u, 30, 0.5, 0.15, 0.30};
  if (dof == 4) return {"rod4", quick ? 400u : 4000u, 10, 1.0, 0.30, 0.50};
  throw InvalidArgument("the static experiments use 2 or 4 DOF, not " + std::to_string(dof));
}

std::size_t testSize(bool quick) {
  return quick ? 1000 : 10000;
}

// Everything one trial needs: a random environment, its exact checkers and a labelled test set.
struct Trial {
  Robot robot;
  Scene scene;
  std::shared_ptr<SceneChecker> fcl;
  Configurations test;
  Labels truth;

  Trial(const Setup& s, bool quick, Rng& rng)
      : robot(loadRobot(s.robot)), scene(randomCubes(4, s.minSide, s.maxSide, s.reach, rng)) {
    fcl = makeSceneChecker("fcl", robot, scene);
    test = uniformConfigurations(robot.limits(), testSize(quick), rng);
    truth = labelConfigurations(*fcl, test);
  }
  double cobsFraction() const {
    return static_cast<double>(std::count(truth.begin(), truth.end(), 1)) /
           static_cast<double>(truth.size());
  }
};

/// The counts of `predict` on the trial's test points against their FCL labels.
template <class Predict>
ConfusionCounts confusion(const Trial& t, const Predict& predict) {
  return confusionOf(t.truth, [&](std::size_t i) {
    return predict(t.test.row(static_cast<Eigen::Index>(i)).data());
  });
}

struct MethodResult {
  std::string method;
  ConfusionCounts counts;
  double support, querySeconds, trainSeconds;
  bool qpStopped = false;  ///< SSVM ended on a QP that missed its tolerance
};

}  // namespace

/// One trial of the static experiment: Fastron, ISVM, SSVM and LIBSVM trained in the trial's
/// world, and the exact checkers, each scored on the trial's test set.
std::vector<MethodResult> runStaticTrial(const Setup& s, const Trial& t, const StaticOptions& o,
                                         Rng& rng, int dof, std::size_t trial,
                                         const Progress& progress) {
  const JointLimits limits = t.robot.limits();
  const auto gjk = makeSceneChecker("gjk", t.robot, t.scene);
  std::vector<MethodResult> results;

  // The training set of Fastron, SSVM and LIBSVM: N uniform configurations labelled by FCL.
  auto start = Clock::now();
  const Configurations q = uniformConfigurations(limits, s.n, rng);
  const Labels y = labelConfigurations(*t.fcl, q);
  const double labelSeconds = since(start);

  auto evaluate = [&](const std::string& name, Classifier& c, double trainSeconds) {
    results.push_back({name, confusion(t, [&](const double* x) { return c.predict(x); }),
                       static_cast<double>(c.supportCount()),
                       meanSecondsPerCall(t.test, [&](const double* x) { return c.predict(x); }),
                       trainSeconds});
  };
  auto trained = [&](Classifier& c) {
    const auto begin = Clock::now();
    c.train(q, y);
    return labelSeconds + since(begin);
  };

  if (progress)
    progress("static " + std::to_string(dof) + "-DOF, trial " + std::to_string(trial + 1) + "/" +
             std::to_string(o.trials) + ": Fastron");
  FastronClassifier fastron(limits, {.kernel = {KernelType::RationalQuadratic, s.gamma},
                                     .beta = o.beta,
                                     .maxIterations = 1'000'000,
                                     .maxSupportPoints = s.n});
  evaluate("Fastron", fastron, trained(fastron));

  if (progress)
    progress("static " + std::to_string(dof) + "-DOF, trial " + std::to_string(trial + 1) +
             ": ISVM");
  IsvmClassifier isvm(limits, {KernelType::Gaussian, s.gamma},
                      {.C = 10,
                       .initialPoints = s.n / 10,
                       .maxAdded = s.n - s.n / 10,
                       .batch = s.n / 20,
                       .seed = rng()});
  start = Clock::now();
  isvm.trainActively([&](const Configurations& a) { return labelConfigurations(*t.fcl, a); });
  evaluate("ISVM", isvm, since(start));

  if (progress)
    progress("static " + std::to_string(dof) + "-DOF, trial " + std::to_string(trial + 1) +
             ": SSVM");
  SsvmClassifier ssvm(limits, {KernelType::RationalQuadratic, s.gamma}, {.C = 10});
  evaluate("SSVM", ssvm, trained(ssvm));
  results.back().qpStopped = ssvm.report().stoppedByQp;

  LibsvmClassifier libsvm(limits, s.gamma, 10);
  evaluate("LIBSVM", libsvm, trained(libsvm));

  const std::size_t d = limits.dim();
  results.push_back({"FK+GJK",
                     confusion(t,
                               [&](const double* x) {
                                 return gjk->inCollision({x, d});
                               }),
                     std::nan(""), meanSecondsPerCheck(t.test, *gjk), std::nan("")});
  results.push_back({"FK+FCL",
                     confusion(t,
                               [&](const double* x) {
                                 return t.fcl->inCollision({x, d});
                               }),
                     std::nan(""), meanSecondsPerCheck(t.test, *t.fcl), std::nan("")});
  return results;
}

Table runStatic(const StaticOptions& o, const Progress& progress) {
  Table table{{"dof", "trial", "method", "accuracy", "tpr", "tnr", "support", "query_s", "train_s",
               "obstacles", "cobs_fraction", "qp_stopped"},
              {}};
  for (const int dof : o.dofs) {
    const Setup s = setupFor(dof, o.quick);
    for (std::size_t trial = 0; trial < o.trials; ++trial) {
      Rng rng(o.seed * 1000 + static_cast<std::uint64_t>(dof) * 100 + trial);
      Trial t(s, o.quick, rng);
      const std::vector<MethodResult> results = runStaticTrial(s, t, o, rng, dof, trial, progress);
      for (const MethodResult& r : results) {
        table.add({std::to_string(dof), std::to_string(trial), r.method, cell(r.counts.accuracy()),
                   cell(r.counts.tpr()), cell(r.counts.tnr()), cell(r.support),
                   cell(r.querySeconds), cell(r.trainSeconds), std::to_string(t.scene.size()),
                   cell(t.cobsFraction()), r.qpStopped ? "1" : "0"});
      }
    }
  }
  return table;
}

Table runStaticSweep(const StaticOptions& o, const std::string& parameter,
                     const Progress& progress) {
  const std::vector<double> values =
      parameter == "beta"    ? std::vector<double>{1, 2, 5, 10, 20, 50, 100, 200, 500, 1000}
      : parameter == "gamma" ? std::vector<double>{1, 2, 5, 10, 20, 30, 50, 100, 200}
                             : throw InvalidArgument("sweep parameter must be beta or gamma");
  Table table{{"dof", "trial", parameter, "accuracy", "tpr", "tnr", "support_ratio"}, {}};
  for (const int dof : o.dofs) {
    const Setup s = setupFor(dof, o.quick);
    for (std::size_t trial = 0; trial < o.trials; ++trial) {
      if (progress)
        progress("static-" + parameter + " " + std::to_string(dof) + "-DOF, trial " +
                 std::to_string(trial + 1) + "/" + std::to_string(o.trials));
      Rng rng(o.seed * 1000 + static_cast<std::uint64_t>(dof) * 100 + trial);
      Trial t(s, o.quick, rng);
      const Configurations q = uniformConfigurations(t.robot.limits(), s.n, rng);
      const Labels y = labelConfigurations(*t.fcl, q);
      for (const double v : values) {
        TrainParams params{
            .kernel = {KernelType::RationalQuadratic, parameter == "gamma" ? v : s.gamma},
            .beta = parameter == "beta" ? v : o.beta,
            .maxIterations = 1'000'000,
            .maxSupportPoints = s.n};
        FastronClassifier fastron(t.robot.limits(), params);
        fastron.train(q, y);
        const ConfusionCounts c = confusion(t, [&](const double* x) { return fastron.predict(x); });
        table.add({std::to_string(dof), std::to_string(trial), cell(v), cell(c.accuracy()),
                   cell(c.tpr()), cell(c.tnr()),
                   cell(static_cast<double>(fastron.supportCount()) / static_cast<double>(s.n))});
      }
    }
  }
  return table;
}

namespace {

// The paper's Fig. 5 tables: |S|, query time, training time.
const std::map<std::pair<int, std::string>, std::array<std::string, 3>> kPaperStatic{
    {{2, "Fastron"}, {"133.6 ± 32.4", "424 ± 90 ns", "231.4 ± 38.3 ms"}},
    {{2, "ISVM"}, {"349.1 ± 128.6", "1.78 ± 0.62 µs", "2.72 ± 1.60 s"}},
    {{2, "SSVM"}, {"52.4 ± 11.3", "220 ± 52 ns", "18.8 ± 2.69 s"}},
    {{2, "FK+GJK"}, {"—", "105.1 ± 16.5 µs", "—"}},
    {{4, "Fastron"}, {"1084.1 ± 206.9", "3.4 ± 0.6 µs", "707.6 ± 75.2 ms"}},
    {{4, "ISVM"}, {"1078.1 ± 125.8", "5.8 ± 0.7 µs", "75.5 ± 20.6 s"}},
    {{4, "SSVM"}, {"509.8 ± 106.3", "1.5 ± 0.3 µs", "193.7 ± 33.6 s"}},
    {{4, "FK+GJK"}, {"—", "166.6 ± 20.0 µs", "—"}},
};

}  // namespace

std::string staticReport(const Table& r, const StaticOptions& o) {
  std::ostringstream md;
  md << "# Static environments (paper, Sec. IV-A, Fig. 5)\n\n"
     << "Rods among up to 4 random cubes, labels from FCL, " << o.trials
     << " trial(s) per robot, seed " << o.seed << (o.quick ? ", quick mode (small N)" : "")
     << ". Mean ± standard deviation over trials; the paper's values "
     << "(MATLAB, GJK labels) beside ours. Training time includes labelling.\n";
  for (const int dof : o.dofs) {
    md << "\n## " << dof
       << " DOF\n\n| Method | |S| | Query time | Training time | Accuracy | TPR | TNR | paper |S| "
          "| paper query | paper training |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string method : {"Fastron", "ISVM", "SSVM", "LIBSVM", "FK+GJK", "FK+FCL"}) {
      const auto paper = kPaperStatic.find({dof, method});
      md << methodRow(r, method, {{"dof", std::to_string(dof)}, {"method", method}}, "train_s",
                      paper == kPaperStatic.end() ? std::array<std::string, 3>{} : paper->second);
    }
    md << "\nC-space in collision: "
       << meanStd(summarize(r.numbers("cobs_fraction",  // one row per trial
                                      {{"dof", std::to_string(dof)}, {"method", "Fastron"}})),
                  3)
       << " of the configurations.\n";
    const std::vector<double> stopped =
        r.numbers("qp_stopped", {{"dof", std::to_string(dof)}, {"method", "SSVM"}});
    const auto early = std::count(stopped.begin(), stopped.end(), 1.0);
    if (early > 0) {
      md << "SSVM ended on a QP that missed its tolerance in " << early << " of " << stopped.size()
         << " trial(s) and kept the weights of its last converged iteration "
            "(docs/experiments.md).\n";
    }
  }
  return md.str();
}

std::string staticSweepReport(const Table& r, const std::string& parameter,
                              const StaticOptions& o) {
  std::ostringstream md;
  md << "# Fastron's " << parameter << " sweep (paper, Fig. " << (parameter == "beta" ? "4" : "6")
     << ")\n\n"
     << "Rods among up to 4 random cubes, FCL labels, " << o.trials << " trial(s), seed " << o.seed
     << (o.quick ? ", quick mode" : "") << ". Mean ± standard deviation over trials.\n";
  for (const int dof : o.dofs) {
    md << "\n## " << dof << " DOF\n\n| " << parameter
       << " | TPR | TNR | accuracy | |S| / N |\n|---|---|---|---|---|\n";
    for (const std::string& value : r.distinct(parameter, {{"dof", std::to_string(dof)}})) {
      const Table::Filter where{{"dof", std::to_string(dof)}, {parameter, value}};
      auto stat = [&](const std::string& column) {
        return meanStd(summarize(r.numbers(column, where)), 3);
      };
      md << "| " << value << " | " << stat("tpr") << " | " << stat("tnr") << " | "
         << stat("accuracy") << " | " << stat("support_ratio") << " |\n";
    }
  }
  return md.str();
}

}  // namespace fastron::experiments
