// fastron.ProxyCollisionDetector: label -> update -> active learning over any oracle, in the
// foreground or on a background thread.

#include <pybind11/stl.h>

#include <memory>

#include "arrays.h"
#include "bindings.h"
#include "detector_holder.h"
#include "fastron/core/error.h"
#include "fastron/proxy/held_out_training.h"
#include "fastron/proxy/proxy_collision_detector.h"
#include "python_checker.h"

namespace fastron::python {

namespace {

/// A checker object, or any callable q -> bool (wrapped in a FunctionChecker of `dof` joints).
std::shared_ptr<const CollisionChecker> oracleOf(py::handle oracle, std::size_t dof) {
  if (py::isinstance<CollisionChecker>(oracle))
    return oracle.cast<std::shared_ptr<CollisionChecker>>();
  if (PyCallable_Check(oracle.ptr()))
    return std::make_shared<PythonChecker>(py::reinterpret_borrow<py::function>(oracle), dof,
                                           "python");
  throw InvalidArgument("oracle: expected a CollisionChecker or a callable q -> bool, got " +
                        typeName(oracle));
}

/// Threads that label for `oracle`: `requested`, but one for a Python oracle, which answers one
/// call at a time (the GIL), so more threads only wait.
unsigned labellingThreads(const CollisionChecker& oracle, unsigned requested) {
  return dynamic_cast<const PythonChecker*>(&oracle) ? 1 : requested;
}

DetectorHolder makeDetector(py::handle oracle, const FeatureMap& features, std::uint64_t seed,
                            std::optional<double> gamma, std::optional<double> beta,
                            std::optional<std::uint32_t> kernelBlock,
                            std::optional<double> wholeShare, bool selfCollisionLabels,
                            std::size_t maxSupport, std::optional<std::size_t> activeSamples,
                            std::optional<bool> coldStart, unsigned labelThreads,
                            std::size_t calibrationSamples, bool relabelSupport) {
  const std::shared_ptr<const CollisionChecker> checker =
      oracleOf(oracle, features.configurationDim());
  ProxyParams params = defaultProxyParams(features.kind(), selfCollisionLabels);
  if (gamma) params.train.kernel.gamma = *gamma;
  if (beta) params.train.beta = *beta;
  if (kernelBlock) params.train.kernel.block = *kernelBlock;
  if (wholeShare) params.train.kernel.wholeShare = *wholeShare;
  params.train.maxSupportPoints = maxSupport;
  if (activeSamples) params.activeLearning.maxSamples = *activeSamples;
  if (coldStart == false) params = withWarmStart(params);  // the paper's update
  if (coldStart == true) params.coldStart = true;
  params.seed = seed;
  params.labelThreads = labellingThreads(*checker, labelThreads);
  params.calibrationSamples = calibrationSamples;
  params.relabelSupport = relabelSupport;
  return DetectorHolder(new ProxyCollisionDetector(checker, features, params));
}

/// trainToHeldOutTargets with `train --scene`'s settings: (Model, [(samples, |S|, counts, grown
/// level, candidate)], index of the round kept).
py::tuple trainScene(
    py::handle oracle, const FeatureMap& features, std::size_t samples, double accuracy, double tpr,
    std::size_t heldOut, std::size_t maxSamples, std::uint64_t seed, bool selfCollisionLabels,
    std::optional<double> gamma, std::optional<double> beta, const py::sequence& grownOracles,
    const std::vector<std::pair<FeatureMap, std::optional<double>>>& alternatives) {
  const std::shared_ptr<const CollisionChecker> checker =
      oracleOf(oracle, features.configurationDim());
  std::vector<std::shared_ptr<const CollisionChecker>> grown;
  std::vector<const CollisionChecker*> grownPointers;
  unsigned threads = labellingThreads(*checker, 0);  // 0: all cores, 1: a Python oracle's
  for (const py::handle g : grownOracles) {
    grown.push_back(oracleOf(g, features.configurationDim()));
    grownPointers.push_back(grown.back().get());
    if (labellingThreads(*grown.back(), 0) == 1) threads = 1;
  }
  TrainParams params = sceneTrainParams(features.kind(), selfCollisionLabels);
  if (gamma) params.kernel.gamma = *gamma;
  if (beta) params.beta = *beta;
  // Each alternative: its features with the same settings, and its own beta where it has one.
  std::vector<ModelCandidate> candidates;
  for (const auto& [alternativeFeatures, alternativeBeta] : alternatives) {
    TrainParams alternative = sceneTrainParams(alternativeFeatures.kind(), selfCollisionLabels);
    if (gamma) alternative.kernel.gamma = *gamma;
    alternative.beta = alternativeBeta.value_or(beta.value_or(alternative.beta));
    candidates.push_back({alternativeFeatures, alternative});
  }
  const HeldOutTargets targets{accuracy, tpr, heldOut, maxSamples};
  HeldOutTraining trained;
  {
    py::gil_scoped_release released;
    Rng rng(seed);
    trained = trainToHeldOutTargets(*checker, features, params, samples, targets, rng, threads,
                                    grownPointers, candidates);
  }
  py::list rounds;
  for (const HeldOutRound& round : trained.rounds) {
    rounds.append(py::make_tuple(round.trainingSamples, round.supportCount, round.heldOut,
                                 round.grownLevel, round.candidate));
  }
  return py::make_tuple(std::const_pointer_cast<Model>(trained.model), rounds, trained.chosenRound);
}

/// answers_missed_by and train_scene.
void bindLabellingAndTraining(py::module_& m) {
  m.def(
      "answers_missed_by",
      [](const Model& model, py::handle x, py::handle y) {
        const ConfigurationRows rows = configurations(x, model.dim(), "X", false);
        const Dataset missed = answersMissedBy(
            model, Dataset{Configurations(rows.matrix()), labels(y, rows.rows, "y"), {}});
        return py::make_tuple(toArray(missed.points), toArray(missed.labels));
      },
      py::arg("model"), py::arg("X"), py::arg("y"),
      "The rows of (X, y) whose label the model gets wrong, as (X, y): the answers worth "
      "learning from a verified plan (plan.exact_answers).");
  m.def("train_scene", &trainScene, py::arg("oracle"), py::arg("features"),
        py::arg("samples") = kSceneSamples, py::kw_only(),
        py::arg("accuracy") = HeldOutTargets{}.accuracy,
        py::arg("tpr") = HeldOutTargets{}.truePositiveRate,
        py::arg("held_out") = HeldOutTargets{}.samplesPerRound,
        py::arg("max_samples") = HeldOutTargets{}.maxTrainingSamples, py::arg("seed") = 1,
        py::arg("self_collision_labels") = false, py::arg("gamma") = py::none(),
        py::arg("beta") = py::none(), py::arg("grown_oracles") = py::tuple(),
        py::arg("alternatives") = std::vector<std::pair<FeatureMap, std::optional<double>>>{},
        "A model of a scene that stands still, as `fastron train --scene` trains it: Algorithm 1 "
        "on `samples` uniform configurations labelled by the oracle, then rounds on `held_out` "
        "fresh ones: while their accuracy or TPR is below the targets and fewer than "
        "max_samples have been learned, learn them with all before and measure on new ones. "
        "grown_oracles: oracles that call more configurations colliding, each more than the "
        "last (FclChecker(robot, scene.grown(m)) for increasing margins m); a round that meets "
        "the accuracy target and misses the TPR makes the next rounds learn the next one's "
        "labels, while every round is still measured on the oracle's. "
        "alternatives: (FeatureMap, beta or None) pairs, other ways to model the same "
        "configurations; a round whose model misses the targets trains each on the same samples "
        "and measures it on the same fresh ones (`fastron train --scene` adds "
        "(robot_features(robot, max_points=5), 10) to its four automatic points). "
        "Returns (Model, rounds, kept): each round (training samples, |S|, ConfusionCounts on "
        "configurations its model had not learned, grown level: 0 the oracle's labels, k the "
        "k-th grown oracle's, candidate: 0 `features`, k the k-th alternative), and the index of "
        "the round whose model, the closest to the targets, is returned. "
        "The GIL is released while it trains (a Python oracle takes it for each call).");
}

/// StepReport and BackgroundHealth.
void bindStepReports(py::module_& m) {
  py::class_<StepReport>(m, "StepReport", "What one initialize() or step() did.")
      .def_readonly("update", &StepReport::update)
      .def_readonly("labelled", &StepReport::labelled, "Oracle calls made.")
      .def_readonly("added", &StepReport::added)
      .def_readonly("observed", &StepReport::observed)
      .def_readonly("model_version", &StepReport::modelVersion)
      .def_property_readonly("seconds", [](const StepReport& r) { return inSeconds(r.total); })
      .def_property_readonly("label_seconds",
                             [](const StepReport& r) { return inSeconds(r.labelTime); })
      .def("__repr__", [](const StepReport& r) {
        return "StepReport(model_version=" + std::to_string(r.modelVersion) +
               ", support_count=" + std::to_string(r.update.supportCount) +
               ", labelled=" + std::to_string(r.labelled) + ")";
      });

  py::class_<BackgroundHealth>(m, "BackgroundHealth", "How the background updates are faring.")
      .def_readonly("steps", &BackgroundHealth::steps, "Background steps that published a model.")
      .def_readonly("faults", &BackgroundHealth::faults,
                    "Background steps the oracle failed (OracleFault); the last good model stayed.")
      .def_readonly("consecutive_faults", &BackgroundHealth::consecutiveFaults,
                    "Faults since the last good step: 0 when healthy.")
      .def_readonly("last_fault", &BackgroundHealth::lastFault)
      .def_readonly("model_version", &BackgroundHealth::modelVersion)
      .def("__repr__", [](const BackgroundHealth& h) {
        return "BackgroundHealth(steps=" + std::to_string(h.steps) +
               ", faults=" + std::to_string(h.faults) +
               ", consecutive_faults=" + std::to_string(h.consecutiveFaults) + ")";
      });
}

/// ProxyCollisionDetector.
void bindDetector(py::module_& m) {
  py::class_<ProxyCollisionDetector, DetectorHolder>(
      m, "ProxyCollisionDetector",
      "Fig. 2 of the paper: keeps a Fastron model of an oracle's C-space current while the world "
      "changes. The oracle is a CollisionChecker (FclChecker, GjkChecker: labels on every core "
      "with the GIL released) or a Python callable q -> bool (called from one thread at a time).")
      .def(py::init(&makeDetector), py::arg("oracle"), py::arg("features"), py::kw_only(),
           py::arg("seed") = 1, py::arg("gamma") = py::none(), py::arg("beta") = py::none(),
           py::arg("kernel_block") = py::none(), py::arg("kernel_whole_share") = py::none(),
           py::arg("self_collision_labels") = false, py::arg("max_support_points") = 3000,
           py::arg("active_samples") = py::none(), py::arg("cold_start") = py::none(),
           py::arg("label_threads") = 0, py::arg("calibration_samples") = 1000,
           py::arg("relabel_support") = true,
           "features: a FeatureMap (robot_features(robot), or FeatureMap.joint_scaling(limits)); "
           "gamma, beta and the kernel's point terms (kernel_block, kernel_whole_share) default "
           "to the values tuned for the kind of features, as do active_samples (new points per "
           "update) and cold_start (Algorithm 1 from zero weights at every update, at most a "
           "fifth of the new points around support points; False: the paper's update): 2500 "
           "and True for task-space features, 500 and False for joints; self_collision_labels=True "
           "(an oracle that checks the robot against itself) selects those tuned for such "
           "labels. relabel_support=False: a world that stands still, whose support points keep "
           "their labels: each step labels only its new points (the same model, fewer oracle "
           "calls).")
      .def("initialize",
           static_cast<StepReport (ProxyCollisionDetector::*)(std::size_t)>(
               &ProxyCollisionDetector::initialize),
           py::arg("samples"), py::call_guard<py::gil_scoped_release>(),
           "Labels `samples` uniform configurations and trains the first model.")
      .def("step", &ProxyCollisionDetector::step, py::call_guard<py::gil_scoped_release>(),
           "One update for a changed world: active learning, relabelling, Algorithm 1. Raises "
           "OracleFault, keeping the model, when the oracle fails.")
      .def("train_static", &trainStatic, py::arg("samples"), py::arg("updates") = 0,
           py::call_guard<py::gil_scoped_release>(),
           "A model of a scene that stands still: initialize(samples), then `updates` steps.")
      .def_property_readonly(
          "model_version",
          [](const ProxyCollisionDetector& d) { return d.calibratedModel().version; },
          "1 for initialize()'s model, +1 per model published after it.")
      .def("background_health", &ProxyCollisionDetector::backgroundHealth,
           "Steps and faults of the background thread since start_background().")
      .def(
          "model",
          [](const ProxyCollisionDetector& d) { return std::const_pointer_cast<Model>(d.model()); },
          "The latest model: an immutable snapshot, safe to query while updates go on.")
      .def(
          "add_observations",
          [](ProxyCollisionDetector& d, py::handle x, py::handle y) {
            const ConfigurationRows rows =
                configurations(x, d.features().configurationDim(), "X", false);
            d.addObservations(
                Dataset{Configurations(rows.matrix()), labels(y, rows.rows, "y"), {}});
          },
          py::arg("X"), py::arg("y"),
          "Exact answers the caller already has, learned at the next step() or "
          "learn_observations() (e.g. a verified plan's answers that answers_missed_by keeps).")
      .def("learn_observations", &ProxyCollisionDetector::learnObservations,
           py::call_guard<py::gil_scoped_release>(),
           "Learns the waiting observations now, asking the oracle nothing (no relabelling, no "
           "active learning): for a scene that has not moved since the last step. The report's "
           "`observed` counts them; nothing waiting, no new model.")
      .def_property_readonly(
          "dropped_observations", &ProxyCollisionDetector::droppedObservations,
          "Observations dropped because 20000 were already waiting (each step or "
          "learn_observations() takes them).")
      .def(
          "start_background",
          [](ProxyCollisionDetector& d, double minPeriod) {
            if (!(minPeriod >= 0)) throw InvalidArgument("min_period must be >= 0 seconds");
            d.startBackground({}, std::chrono::duration_cast<std::chrono::nanoseconds>(
                                      std::chrono::duration<double>(minPeriod)));
          },
          py::arg("min_period") = 0.0,
          "Runs step() in a loop on a background thread, at most once per min_period seconds.")
      .def("stop_background", &ProxyCollisionDetector::stopBackground,
           py::call_guard<py::gil_scoped_release>(),
           "Stops the background thread; raises what ended it, if anything did.")
      .def_property_readonly("background_running", &ProxyCollisionDetector::backgroundRunning)
      .def_property_readonly("features", &ProxyCollisionDetector::features)
      .def_property_readonly("limits", &ProxyCollisionDetector::limits);
}

}  // namespace

void bindProxy(py::module_& m) {
  bindLabellingAndTraining(m);
  bindStepReports(m);
  bindDetector(m);
}

}  // namespace fastron::python
