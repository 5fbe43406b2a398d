// The recipes the command runs, for Python: the same functions, so the same model for the same
// seed.

#include <pybind11/stl.h>

#include "bindings.h"
#include "detector_holder.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/pipeline/held_out_model.h"
#include "fastron/pipeline/scene_model.h"

namespace fastron::python {

namespace py = pybind11;

namespace {

/// train_scene_model: the default method's model of a scene.
void bindSceneModel(py::module_& m) {
  const pipeline::SceneModelOptions defaults;
  m.def(
      "train_scene_model",
      [](const Robot& robot, const Scene& scene, const std::optional<FeatureMap>& features,
         std::size_t samples, std::size_t updates, std::uint64_t seed, std::optional<double> gamma,
         std::optional<double> beta, bool selfCollision, double padding,
         const std::string& checker) {
        // No features given: the automatic rules' candidates, as `fastron plan` chooses.
        const std::vector<pipeline::FeatureCandidate> candidates =
            features ? std::vector<pipeline::FeatureCandidate>{{"given", *features}}
                     : pipeline::automaticFeatureCandidates(robot, FeatureKind::Kinematic);
        pipeline::SceneModel model;
        {
          py::gil_scoped_release released;
          CheckerOptions checking;
          checking.selfCollision = selfCollision;
          checking.padding = padding;
          model = pipeline::trainSceneModel(robot, scene, checking, candidates,
                                            {samples, updates, seed, gamma, beta, checker});
        }
        return DetectorHolder(model.detector.release());
      },
      py::arg("robot"), py::arg("scene"), py::arg("features") = py::none(), py::kw_only(),
      py::arg("samples") = defaults.samples, py::arg("updates") = defaults.updates,
      py::arg("seed") = 1, py::arg("gamma") = py::none(), py::arg("beta") = py::none(),
      py::arg("self_collision") = false, py::arg("padding") = 0.0,
      py::arg("checker") = defaults.checker,
      "The default method's model of a scene (what `fastron plan` trains, the same function): "
      "a ProxyCollisionDetector of the scene's obstacles alone (its oracle the exact checker "
      "`checker` (scene_checker_names()) without self-collision; `self_collision` and `padding` "
      "are the exact checker's), trained on `samples` labels and `updates` active-learning "
      "updates, no band. Without `features`, the control points of the spread and the cover "
      "rules are both trained on the same labels and the one better on 500 held-out labels is "
      "kept. Plan with it as "
      "`fastron plan` does: plan_verified(detector, exact, start, goal, static_scene=True, "
      "oracle_relaxes_exact=True).");
}

/// train_held_out_model: the model of fastron train --robot --scene.
void bindHeldOutModel(py::module_& m) {
  const pipeline::HeldOutModelOptions heldOut;
  m.def(
      "train_held_out_model",
      [](const Robot& robot, const Scene& scene, const std::string& features, std::size_t samples,
         std::size_t heldOutSamples, double targetAccuracy, double targetTpr,
         std::size_t maxSamples, const std::vector<double>& margins, bool selfCollision,
         std::optional<double> gamma, std::optional<double> beta, bool otherCandidates,
         std::uint64_t seed, const std::string& checker) {
        const FeatureKind kind = parseFeatureKind(features);
        // As fastron train --robot --scene: control points for a point-terms model of obstacles
        // (pipeline::heldOutControlPoints).
        const ControlPointOptions automatic = pipeline::heldOutControlPoints(selfCollision);
        const FeatureMap map =
            kind == FeatureKind::Kinematic
                ? robotFeatures(robot, kind, defaultControlPoints(robot, automatic))
                : robotFeatures(robot, kind);
        TrainParams params = sceneTrainParams(map.kind(), selfCollision);
        if (gamma) params.kernel.gamma = *gamma;
        if (beta) params.beta = *beta;
        pipeline::HeldOutModelOptions options;
        options.samples = samples;
        options.targets = {targetAccuracy, targetTpr, heldOutSamples, maxSamples};
        options.margins = margins;
        options.selfCollision = selfCollision;
        options.checker = checker;
        if (otherCandidates) options.automatic = automatic;
        options.candidateBeta = beta;
        options.seed = seed;
        pipeline::HeldOutModel made;
        {
          py::gil_scoped_release released;
          made = pipeline::trainHeldOutModel(robot, scene, map, params, options);
        }
        py::list rounds;
        for (const HeldOutRound& r : made.training.rounds) {
          rounds.append(py::dict(
              py::arg("training_samples") = r.trainingSamples,
              py::arg("support_count") = r.supportCount, py::arg("accuracy") = r.heldOut.accuracy(),
              py::arg("tpr") = r.heldOut.tpr(),
              py::arg("grown_margin") = r.grownLevel == 0 ? 0.0 : made.margins[r.grownLevel - 1],
              py::arg("candidate") = r.candidate));
        }
        return py::make_tuple(std::make_shared<Model>(*made.training.model), rounds,
                              made.training.chosenRound);
      },
      py::arg("robot"), py::arg("scene"), py::kw_only(), py::arg("features") = "fk",
      py::arg("samples") = heldOut.samples, py::arg("held_out") = heldOut.targets.samplesPerRound,
      py::arg("target_accuracy") = heldOut.targets.accuracy,
      py::arg("target_tpr") = heldOut.targets.truePositiveRate,
      py::arg("max_samples") = heldOut.targets.maxTrainingSamples,
      py::arg("margins") = heldOut.margins, py::arg("self_collision") = false,
      py::arg("gamma") = py::none(), py::arg("beta") = py::none(),
      py::arg("other_candidates") = true, py::arg("seed") = 1, py::arg("checker") = heldOut.checker,
      "The most accurate model of a scene that stands still, by the function `fastron train "
      "--robot R --scene S` calls (the same seed gives the command's model): `samples` labels "
      "of the exact checker `checker`, then rounds of `held_out` fresh configurations until "
      "accuracy and TPR reach the "
      "targets (obstacles grown by `margins` when only the TPR is missed; with 'fk' features "
      "and other_candidates, one more control point by each rule tried too). Returns (model, "
      "rounds, kept): each round's training samples, |S|, held-out accuracy and TPR, grown "
      "margin and candidate (0: the first features), and the index of the round kept.");
}

}  // namespace

void bindPipeline(py::module_& m) {
  bindSceneModel(m);
  bindHeldOutModel(m);
}

}  // namespace fastron::python
