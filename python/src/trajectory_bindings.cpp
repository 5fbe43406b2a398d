// Trajectory optimisation on a model's collision cost (issue 53): the cost and its gradient along
// a path, the CHOMP-style optimiser, and the recipe that verifies its path exactly.

#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "fastron/core/error.h"
#include "fastron/planning/collision_cost.h"
#include "fastron/planning/trajectory_optimization.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron::python {

namespace {

TrajectoryOptions trajectoryOptions(double spacing, double margin, double maxStep, double smoothing,
                                    std::size_t maxIterations, double modelResolution,
                                    double timeLimit) {
  TrajectoryOptions options{.spacing = spacing,
                            .margin = margin,
                            .maxStep = maxStep,
                            .smoothing = smoothing,
                            .maxIterations = maxIterations,
                            .timeLimit = timeLimit,
                            .modelResolution = modelResolution};
  validate(options);
  return options;
}

struct PythonTrajectory {
  py::array_t<double> path;
  bool freeOnModel = false;
  std::size_t iterations = 0;
  std::vector<double> costs;
  double seconds = 0;
};

struct PythonVerifiedTrajectory {
  std::string status, failure;
  py::array_t<double> path;
  std::size_t rounds = 0, iterations = 0;
  double optimizeSeconds = 0, verifySeconds = 0, learnSeconds = 0;
  std::vector<double> costs;
};

const TrajectoryOptions kDefaults{};

void bindResults(py::module_& m) {
  py::class_<PythonTrajectory>(m, "OptimizedTrajectory",
                               "A path optimised on a model (optimize_trajectory).")
      .def_readonly("path", &PythonTrajectory::path, "Waypoints (k, d), the same ends.")
      .def_readonly("free_on_model", &PythonTrajectory::freeOnModel,
                    "Every state of the path at model_resolution is free on the model.")
      .def_readonly("iterations", &PythonTrajectory::iterations)
      .def_readonly("costs", &PythonTrajectory::costs,
                    "The path's collision cost before each iteration, and at the end.")
      .def_readonly("seconds", &PythonTrajectory::seconds)
      .def("__repr__", [](const PythonTrajectory& t) {
        return "OptimizedTrajectory(" + std::to_string(t.path.shape(0)) + " waypoints, " +
               std::to_string(t.iterations) +
               " iterations, free_on_model=" + (t.freeOnModel ? "True" : "False") + ")";
      });
  py::class_<PythonVerifiedTrajectory>(m, "VerifiedTrajectory",
                                       "An optimised path checked exactly (optimize_verified).")
      .def_readonly("status", &PythonVerifiedTrajectory::status)
      .def_property_readonly(
          "solved", [](const PythonVerifiedTrajectory& t) { return t.status == "solved"; },
          "True only when the exact checker found the path free.")
      .def_readonly("failure", &PythonVerifiedTrajectory::failure)
      .def_readonly("path", &PythonVerifiedTrajectory::path, "Waypoints (k, d).")
      .def_readonly("rounds", &PythonVerifiedTrajectory::rounds,
                    "Optimisations: 1 + the times the model learned and went on.")
      .def_readonly("iterations", &PythonVerifiedTrajectory::iterations)
      .def_readonly("optimize_seconds", &PythonVerifiedTrajectory::optimizeSeconds)
      .def_readonly("verify_seconds", &PythonVerifiedTrajectory::verifySeconds)
      .def_readonly("learn_seconds", &PythonVerifiedTrajectory::learnSeconds)
      .def_readonly("costs", &PythonVerifiedTrajectory::costs,
                    "The first optimisation's collision cost per iteration.")
      .def("__repr__", [](const PythonVerifiedTrajectory& t) {
        return "VerifiedTrajectory('" + t.status + "', " + std::to_string(t.path.shape(0)) +
               " waypoints, " + std::to_string(t.rounds) + " rounds)";
      });
}

/// path_collision_cost and straight_path.
void bindCost(py::module_& m) {
  m.def(
      "path_collision_cost",
      [](const Model& model, py::handle path, double margin) {
        const ConfigurationRows rows = configurations(path, model.dim(), "path", false);
        PathCollisionCost cost;
        {
          py::gil_scoped_release released;
          cost = pathCollisionCost(model, rows.matrix(), margin);
        }
        return py::make_tuple(cost.cost, toArray(cost.gradient), toArray(cost.scores));
      },
      py::arg("model"), py::arg("path"), py::kw_only(), py::arg("margin") = kDefaults.margin,
      "The model's collision cost along path (k, d): the trapezoid integral over its polyline of "
      "c(q) = 1/2 max(0, f(q) + margin)^2. Returns (cost, gradient (k, d) with respect to every "
      "waypoint, scores (k,)).");
  m.def(
      "straight_path",
      [](py::handle start, py::handle goal, double spacing) {
        const ConfigurationRows a = configurations(start, 0, "start");
        const Eigen::VectorXd from = vector(start, a.cols, "start");
        const Eigen::VectorXd to = vector(goal, a.cols, "goal");
        return pathArray(straightPath(from, to, spacing), a.cols);
      },
      py::arg("start"), py::arg("goal"), py::kw_only(), py::arg("spacing") = kDefaults.spacing,
      "Waypoints (k, d) from start to goal on a straight line, at most `spacing` apart (k >= 8).");
}

}  // namespace

void bindTrajectories(py::module_& m) {
  bindResults(m);
  bindCost(m);
  m.def(
      "optimize_trajectory",
      [](const Model& model, py::handle path, double margin, double maxStep, double smoothing,
         std::size_t maxIterations, double modelResolution, double timeLimit) {
        const JointPath initial = pathOf(path, model.dim());
        const TrajectoryOptions options =
            trajectoryOptions(kDefaults.spacing, margin, maxStep, smoothing, maxIterations,
                              modelResolution, timeLimit);
        OptimizedTrajectory out;
        {
          py::gil_scoped_release released;
          out = optimizeTrajectory(model, model.limits(), initial, options);
        }
        return PythonTrajectory{pathArray(out.path, model.dim()), out.freeOnModel, out.iterations,
                                out.costs, inSeconds(out.time)};
      },
      py::arg("model"), py::arg("path"), py::kw_only(), py::arg("margin") = kDefaults.margin,
      py::arg("max_step") = kDefaults.maxStep, py::arg("smoothing") = kDefaults.smoothing,
      py::arg("max_iterations") = kDefaults.maxIterations,
      py::arg("model_resolution") = kDefaults.modelResolution,
      py::arg("time_limit") = kDefaults.timeLimit,
      "Moves the interior waypoints of path (k, d), k >= 3, out of the model's collisions "
      "(CHOMP's covariant gradient descent on the collision cost, each step scaled to `max_step` "
      "joint units, `smoothing` of the way back to the straight line per iteration), within the "
      "model's joint limits, for at most `time_limit` seconds (0: no limit). The result is the "
      "model's word: check it with check_path.");
  m.def(
      "optimize_verified",
      [](ProxyCollisionDetector& detector, const std::shared_ptr<CollisionChecker>& exact,
         py::handle start, py::handle goal, double resolution, double spacing, double margin,
         double maxStep, double smoothing, std::size_t maxIterations, double modelResolution,
         double timeLimit, std::size_t rounds) {
        const std::size_t dim = detector.limits().dim();
        const Eigen::VectorXd a = vector(start, dim, "start"), b = vector(goal, dim, "goal");
        const TrajectoryOptions options = trajectoryOptions(
            spacing, margin, maxStep, smoothing, maxIterations, modelResolution, timeLimit);
        VerifiedTrajectory out;
        {
          py::gil_scoped_release released;
          out = optimizeVerified(detector, exact, a, b, resolution, options, rounds);
        }
        return PythonVerifiedTrajectory{std::string(toString(out.status)),
                                        out.failure,
                                        pathArray(out.path, dim),
                                        out.rounds,
                                        out.iterations,
                                        inSeconds(out.optimizeTime),
                                        inSeconds(out.verifyTime),
                                        inSeconds(out.learnTime),
                                        out.costs};
      },
      py::arg("detector"), py::arg("exact"), py::arg("start"), py::arg("goal"), py::kw_only(),
      py::arg("resolution") = 0.02, py::arg("spacing") = kDefaults.spacing,
      py::arg("margin") = kDefaults.margin, py::arg("max_step") = kDefaults.maxStep,
      py::arg("smoothing") = kDefaults.smoothing,
      py::arg("max_iterations") = kDefaults.maxIterations,
      py::arg("model_resolution") = kDefaults.modelResolution,
      py::arg("time_limit") = kDefaults.timeLimit, py::arg("rounds") = 4,
      "From the straight line between start and goal: optimises on the detector's model, checks "
      "the path with `exact` every `resolution`, and while it collides (up to `rounds` times) "
      "lets the detector learn the answers its model got wrong and optimises on, for at most "
      "`time_limit` seconds in all (0: no limit). solved is True "
      "only when `exact` found the path free. Not while the detector updates in the background.");
}

}  // namespace fastron::python
