// The recipes the command runs, for Python: the same functions, so the same model for the same
// seed.

#include <pybind11/stl.h>

#include "bindings.h"
#include "detector_holder.h"
#include "fastron/geometry/control_points.h"
#include "fastron/pipeline/scene_model.h"

namespace fastron::python {

namespace py = pybind11;

void bindPipeline(py::module_& m) {
  const pipeline::SceneModelOptions defaults;
  m.def(
      "train_scene_model",
      [](const Robot& robot, const Scene& scene, const std::optional<FeatureMap>& features,
         std::size_t samples, std::size_t updates, std::uint64_t seed, std::optional<double> gamma,
         std::optional<double> beta, bool selfCollision, double padding) {
        const FeatureMap map = features ? *features : robotFeatures(robot, FeatureKind::Kinematic);
        pipeline::SceneModel model;
        {
          py::gil_scoped_release released;
          model = pipeline::trainSceneModel(robot, scene, {selfCollision, padding}, map,
                                            {samples, updates, seed, gamma, beta});
        }
        return DetectorHolder(model.detector.release());
      },
      py::arg("robot"), py::arg("scene"), py::arg("features") = py::none(), py::kw_only(),
      py::arg("samples") = defaults.samples, py::arg("updates") = defaults.updates,
      py::arg("seed") = 1, py::arg("gamma") = py::none(), py::arg("beta") = py::none(),
      py::arg("self_collision") = false, py::arg("padding") = 0.0,
      "The default method's model of a scene (what `fastron plan` trains, the same function): "
      "a ProxyCollisionDetector of the scene's obstacles alone (its oracle FCL without "
      "self-collision; `self_collision` and `padding` are the exact checker's), trained on "
      "`samples` FCL labels and `updates` active-learning updates, no band. Plan with it as "
      "`fastron plan` does: plan_verified(detector, exact, start, goal, static_scene=True, "
      "oracle_relaxes_exact=True).");
}

}  // namespace fastron::python
