// Planning with OMPL on a model or an exact checker, and verify-and-repair.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.h"
#include "bindings.h"
#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/robot.h"
#include "fastron/planning/motion.h"
#include "fastron/planning/planner.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron::python {

namespace {

PlannerOptions plannerOptions(const std::string& planner, double range, std::size_t rangeStage,
                              double resolution, double modelResolution, double timeLimit,
                              double simplifyTime, const std::string& simplification) {
  PlannerOptions options;
  options.type = parsePlannerType(planner);
  options.range = range;
  options.rangeStage = rangeStage;
  options.resolution = resolution;
  options.modelResolution = modelResolution;
  options.timeLimit = timeLimit;
  options.simplifyTime = simplifyTime;
  options.simplification = parsePathSimplification(simplification);
  validate(options);
  return options;
}

/// plan_verified's settings of the pipeline beyond the plan itself (VerifyRepairOptions' shares and
/// planVerifiedLearning's), as Python passes them.
struct PipelineSettings {
  double approximateShare, substituteShare, stretchShare, bridgeMargin;
  std::size_t enclosedAfter;
  unsigned learningRounds;
  bool learns;  ///< planVerifiedLearning plans: static_scene, or learning_rounds > 0
  std::optional<double> modelShare, hybridRange;
  bool oracleRelaxesExact, gradientRepair;
};

/// Sets `settings` on `options`; throws InvalidArgument naming a setting that only a detector's
/// static-scene plan reads when it was given for another.
void applyPipeline(const PipelineSettings& settings, PlannerOptions& options) {
  options.verify.approximateShare = settings.approximateShare;
  options.verify.substituteShare = settings.substituteShare;
  options.verify.stretchShare = settings.stretchShare;
  options.verify.bridgeMargin = settings.bridgeMargin;
  options.enclosedAfter = settings.enclosedAfter;
  options.verify.learningRounds = settings.learningRounds;
  for (const auto& [given, name] : {std::pair{settings.modelShare.has_value(), "model_share"},
                                    std::pair{settings.hybridRange.has_value(), "hybrid_range"},
                                    std::pair{settings.oracleRelaxesExact, "oracle_relaxes_exact"},
                                    std::pair{settings.gradientRepair, "gradient_repair"}}) {
    if (given && !settings.learns) {
      throw InvalidArgument(std::string(name) +
                            ": only a ProxyCollisionDetector's plan in a static scene reads it "
                            "(static_scene=True)");
    }
  }
  if (settings.modelShare) options.verify.modelShare = *settings.modelShare;
  if (settings.hybridRange) options.verify.hybridRange = *settings.hybridRange;
  options.verify.oracleRelaxesExact = settings.oracleRelaxesExact;
  options.verify.gradientRepair = settings.gradientRepair;
  validate(options);
}

/// The joint limits of a planning problem: given, else the source's own (a model's or a
/// detector's, or the robot's of a SceneChecker).
JointLimits limitsOf(py::handle source, const std::optional<JointLimits>& given) {
  if (given) return *given;
  if (py::isinstance<Model>(source)) return source.cast<const Model&>().limits();
  if (py::isinstance<ProxyCollisionDetector>(source))
    return source.cast<const ProxyCollisionDetector&>().limits();
  if (py::isinstance<SceneChecker>(source))
    return source.cast<const SceneChecker&>().robot().limits();
  throw InvalidArgument("limits=: this collision source has no joint limits of its own");
}

CollisionSource sourceOf(py::handle source) {
  if (py::isinstance<Model>(source))
    return std::shared_ptr<const Model>(source.cast<std::shared_ptr<Model>>());
  if (py::isinstance<CollisionChecker>(source))
    return std::shared_ptr<const CollisionChecker>(
        source.cast<std::shared_ptr<CollisionChecker>>());
  throw InvalidArgument("source: expected a Model or a CollisionChecker, got " + typeName(source));
}

/// What a plan returns to Python: the path as an (k, d) array beside the report.
struct PythonPlan {
  std::string status;
  py::array_t<double> path;
  double seconds = 0, simplifySeconds = 0, range = 0;
};

struct PythonVerifiedPlan {
  std::string status, failure, plannedOn;
  py::array_t<double> path;
  double planSeconds = 0, verifySeconds = 0, repairSeconds = 0;
  std::size_t invalidStretches = 0, gradientRepairs = 0, relearned = 0;
  bool wholePathReplanned = false;
  py::array_t<double> exactX;
  py::array_t<std::int8_t> exactY;
  py::list attempts;  // (source, status, seconds, checks, check seconds) per plan
  std::uint64_t exactChecks = 0, relaxedChecks = 0;
};

py::list attemptsOf(const VerifiedPlan& plan) {
  py::list attempts;
  for (const PlanAttempt& a : plan.attempts) {
    attempts.append(py::make_tuple(a.source, std::string(toString(a.status)), inSeconds(a.time),
                                   a.checks, inSeconds(a.checkTime)));
  }
  return attempts;
}

PythonVerifiedPlan toPython(const VerifiedPlan& plan, std::size_t dim) {
  return {std::string(toString(plan.status)),
          plan.failure,
          plan.plannedOn,
          pathArray(plan.path, dim),
          inSeconds(plan.planTime),
          inSeconds(plan.verifyTime),
          inSeconds(plan.repairTime),
          plan.invalidStretches,
          plan.gradientRepairs,
          plan.relearned,
          plan.wholePathReplanned,
          toArray(plan.exactAnswers.points),
          toArray(plan.exactAnswers.labels),
          attemptsOf(plan),
          plan.exactChecks,
          plan.relaxedChecks};
}

/// PlanResult and VerifiedPlan.
void bindPlanResults(py::module_& m) {
  py::class_<PythonPlan>(m, "PlanResult", "One planning query on one collision source.")
      .def_readonly("status", &PythonPlan::status,
                    "'solved', 'start in collision', 'goal in collision' or 'timeout'.")
      .def_property_readonly("solved", [](const PythonPlan& p) { return p.status == "solved"; })
      .def_readonly("path", &PythonPlan::path, "Waypoints (k, d), start to goal; empty if none.")
      .def_readonly("seconds", &PythonPlan::seconds)
      .def_readonly("simplify_seconds", &PythonPlan::simplifySeconds)
      .def_readonly("range", &PythonPlan::range,
                    "The planner's range when it stopped (0 for BIT*, which has none).")
      .def("__repr__", [](const PythonPlan& p) {
        return "PlanResult('" + p.status + "', " + std::to_string(p.path.shape(0)) + " waypoints)";
      });

  py::class_<PythonVerifiedPlan>(m, "VerifiedPlan",
                                 "A plan on an approximate source, verified and repaired on the "
                                 "exact checker: `path` is valid under it when solved.")
      .def_readonly("status", &PythonVerifiedPlan::status)
      .def_property_readonly("solved",
                             [](const PythonVerifiedPlan& p) { return p.status == "solved"; })
      .def_readonly("path", &PythonVerifiedPlan::path)
      .def_readonly("failure", &PythonVerifiedPlan::failure)
      .def_readonly("planned_on", &PythonVerifiedPlan::plannedOn)
      .def_readonly("plan_seconds", &PythonVerifiedPlan::planSeconds)
      .def_readonly("verify_seconds", &PythonVerifiedPlan::verifySeconds)
      .def_readonly("repair_seconds", &PythonVerifiedPlan::repairSeconds)
      .def_property_readonly("total_seconds",
                             [](const PythonVerifiedPlan& p) {
                               return p.planSeconds + p.verifySeconds + p.repairSeconds;
                             })
      .def_readonly("invalid_stretches", &PythonVerifiedPlan::invalidStretches)
      .def_readonly("gradient_repairs", &PythonVerifiedPlan::gradientRepairs,
                    "Of invalid_stretches, those gradient repair freed without replanning.")
      .def_readonly("relearned", &PythonVerifiedPlan::relearned,
                    "Paths on the model that verification found colliding and the detector "
                    "learned from before planning again (learning_rounds).")
      .def_readonly("whole_path_replanned", &PythonVerifiedPlan::wholePathReplanned)
      .def_readonly(
          "attempts", &PythonVerifiedPlan::attempts,
          "Where the planning time went: (source, status, seconds, checks, seconds of those "
          "checks) of every plan before verification, in order (the model, its hybrid, "
          "the exact checker).")
      .def_readonly("exact_checks", &PythonVerifiedPlan::exactChecks,
                    "Configurations the exact checker answered for this plan.")
      .def_readonly("relaxed_checks", &PythonVerifiedPlan::relaxedChecks,
                    "Those the detector's oracle answered in its place (oracle_relaxes_exact).")
      .def_property_readonly(
          "exact_answers",
          [](const PythonVerifiedPlan& p) { return py::make_tuple(p.exactX, p.exactY); },
          "Every exact answer of verify and repair as (X, y), for add_observations.")
      .def("__repr__", [](const PythonVerifiedPlan& p) {
        return "VerifiedPlan('" + p.status + "', " + std::to_string(p.path.shape(0)) +
               " waypoints, " + std::to_string(p.invalidStretches) + " stretches repaired)";
      });
}

/// plan: one query on one collision source.
void bindPlan(py::module_& m) {
  m.def(
      "plan",
      [](py::handle source, py::handle start, py::handle goal, std::optional<JointLimits> limits,
         const std::string& planner, double range, std::size_t rangeStage, double resolution,
         double modelResolution, double timeLimit, double simplifyTime,
         const std::string& simplification) {
        const CollisionSource s = sourceOf(source);
        const JointLimits l = limitsOf(source, limits);
        const Eigen::VectorXd a = vector(start, l.dim(), "start"),
                              b = vector(goal, l.dim(), "goal");
        const PlannerOptions options =
            plannerOptions(planner, range, rangeStage, resolution, modelResolution, timeLimit,
                           simplifyTime, simplification);
        PlanResult result;
        {
          py::gil_scoped_release released;
          result = planMotion(s, l, a, b, options);
        }
        return PythonPlan{std::string(toString(result.status)), pathArray(result.path, l.dim()),
                          inSeconds(result.time), inSeconds(result.simplifyTime), result.range};
      },
      py::arg("source"), py::arg("start"), py::arg("goal"), py::kw_only(),
      py::arg("limits") = py::none(), py::arg("planner") = "RRTConnect", py::arg("range") = 0.0,
      py::arg("range_stage") = PlannerOptions{}.rangeStage, py::arg("resolution") = 0.02,
      py::arg("model_resolution") = 0.0, py::arg("time_limit") = 10.0,
      py::arg("simplify_time") = 0.1, py::arg("simplification") = "full",
      "Plans from start to goal with OMPL (planner: 'RRT', 'RRTConnect', 'RRT*', 'BIT*') on a "
      "Model or a CollisionChecker, then shortens the path with OMPL's PathSimplifier for at most "
      "`simplify_time` seconds ('full': simplify, with B-spline smoothing, as MoveIt; "
      "'shortcuts': shortcutting and vertex reduction only, fewer checks). Edges are checked "
      "every `resolution`, on a model (or a checker answering from one) every "
      "`model_resolution` (0: 3 times `resolution`). RRT-Connect's `range` (0: OMPL's "
      "default) is halved after `range_stage` iterations without a path, down to an eighth, "
      "then taken again, each round of ranges twice as long (0: it stays).");
}

/// plan_verified: a plan on an approximate source, verified and repaired.
void bindPlanVerified(py::module_& m) {
  m.def(
      "plan_verified",
      [](py::handle approximate, const std::shared_ptr<CollisionChecker>& exact, py::handle start,
         py::handle goal, std::optional<JointLimits> limits, const std::string& planner,
         double range, std::size_t rangeStage, double resolution, double modelResolution,
         double timeLimit, double simplifyTime, const std::string& simplification,
         unsigned learningRounds, bool staticScene, double approximateShare,
         std::optional<double> modelShare, double substituteShare, double stretchShare,
         double bridgeMargin, std::size_t enclosedAfter, std::optional<double> hybridRange,
         bool oracleRelaxesExact, bool gradientRepair) {
        PlannerOptions options =
            plannerOptions(planner, range, rangeStage, resolution, modelResolution, timeLimit,
                           simplifyTime, simplification);
        const bool learns = staticScene || learningRounds > 0;
        if (learns && !py::isinstance<ProxyCollisionDetector>(approximate)) {
          throw InvalidArgument(
              std::string(learningRounds > 0 ? "learning_rounds" : "static_scene") +
              ": only a ProxyCollisionDetector learns, got " + typeName(approximate));
        }
        applyPipeline(
            {approximateShare, substituteShare, stretchShare, bridgeMargin, enclosedAfter,
             learningRounds, learns, modelShare, hybridRange, oracleRelaxesExact, gradientRepair},
            options);
        const JointLimits l = limitsOf(approximate, limits);
        const Eigen::VectorXd a = vector(start, l.dim(), "start"),
                              b = vector(goal, l.dim(), "goal");
        VerifiedPlan plan;
        if (learns) {
          auto& detector = approximate.cast<ProxyCollisionDetector&>();
          py::gil_scoped_release released;
          plan = planVerifiedLearning(detector, exact, l, a, b, options);
        } else if (py::isinstance<ProxyCollisionDetector>(approximate)) {
          // A detector gives its calibrated band: a model that closes a passage is retried as a
          // hybrid of model and exact checker before planning on the exact one.
          const CalibratedModel model =
              approximate.cast<const ProxyCollisionDetector&>().calibratedModel();
          py::gil_scoped_release released;
          plan = planVerified(model, exact, l, a, b, options);
        } else {
          const CollisionSource source = sourceOf(approximate);
          py::gil_scoped_release released;
          plan = planVerified(source, exact, l, a, b, options);
        }
        return toPython(plan, l.dim());
      },
      py::arg("approximate"), py::arg("exact"), py::arg("start"), py::arg("goal"), py::kw_only(),
      py::arg("limits") = py::none(), py::arg("planner") = "RRTConnect", py::arg("range") = 0.0,
      py::arg("range_stage") = PlannerOptions{}.rangeStage, py::arg("resolution") = 0.02,
      py::arg("model_resolution") = 0.0, py::arg("time_limit") = 10.0,
      py::arg("simplify_time") = 0.1, py::arg("simplification") = "full",
      py::arg("learning_rounds") = 0u, py::arg("static_scene") = false,
      py::arg("approximate_share") = PlannerOptions{}.verify.approximateShare,
      py::arg("model_share") = py::none(),
      py::arg("substitute_share") = PlannerOptions{}.verify.substituteShare,
      py::arg("stretch_share") = PlannerOptions{}.verify.stretchShare,
      py::arg("bridge_margin") = PlannerOptions{}.verify.bridgeMargin,
      py::arg("enclosed_after") = PlannerOptions{}.enclosedAfter,
      py::arg("hybrid_range") = py::none(), py::arg("oracle_relaxes_exact") = false,
      py::arg("gradient_repair") = false,
      "Plans on `approximate` (a Model, a ProxyCollisionDetector's latest model with its band, "
      "or a checker), then verifies every edge with `exact` and replans the stretches that "
      "collide: a solved plan's path never collides under `exact` at `resolution`, whatever "
      "`model_resolution`, the step of edges on the model (0: 3 times `resolution`). "
      "static_scene=True (a detector of a scene that stands still, not updating in the "
      "background): plan as `fastron plan` does, on the model for `model_share` of the time "
      "limit, then on a hybrid trusting the model's 'free' and asking `exact` (the detector's "
      "oracle with oracle_relaxes_exact=True) about its 'collides', with tree edges of "
      "`hybrid_range`. learning_rounds=N (implies static_scene): when verification finds the "
      "model's path colliding, the detector first learns the answers its model got wrong and "
      "plans again, up to N times, before repairing. gradient_repair=True (static_scene): before "
      "a colliding stretch is replanned, the model learns its exact answers and pushes it out "
      "along its collision cost's gradient; kept only when `exact` finds it free. The shares are "
      "of `time_limit`: "
      "docs/planning.md and PlannerOptions in fastron/planning/planner.h.");
}

/// Path checks and path files.
void bindPaths(py::module_& m) {
  m.def(
      "check_path",
      [](const CollisionChecker& checker, py::handle path, double resolution) {
        const JointPath p = pathOf(path, checker.dof());
        py::gil_scoped_release released;
        return checkPath(checker, p, resolution).valid();
      },
      py::arg("checker"), py::arg("path"), py::arg("resolution"),
      "True when every waypoint of path (k, d) and every edge, checked at `resolution`, is free.");

  m.def(
      "states_along_path",
      [](py::handle path, double resolution) {
        const ConfigurationRows rows = configurations(path, 0, "path", false);
        return toArray(statesAlongPath(pathOf(path, rows.cols), resolution));
      },
      py::arg("path"), py::arg("resolution"),
      "Every state a check of path (k, d) at `resolution` looks at, in the path's order: each "
      "waypoint, then the states of the edge that leaves it (as check_path cuts it).");
  m.def(
      "write_path",
      [](const std::filesystem::path& file, py::handle path, const Robot& robot) {
        writePathCsv(pathOf(path, robot.dof()), robot.actuatedJointNames(), file);
      },
      py::arg("file"), py::arg("path"), py::arg("robot"),
      "Writes path (k, d) as CSV, a header of the robot's joint names first (fastron plan --out's "
      "format, read by fastron eval --path).");
  m.def(
      "read_path",
      [](const std::filesystem::path& file, const Robot& robot) {
        return pathArray(readPathCsv(file, robot.actuatedJointNames()), robot.dof());
      },
      py::arg("file"), py::arg("robot"),
      "Reads a path CSV (fastron plan --out's format) of this robot's joints as a (k, d) array; "
      "raises FileError naming the file, line and column of a problem.");
}

}  // namespace

void bindPlanning(py::module_& m) {
  bindPlanResults(m);
  bindPlan(m);
  bindPlanVerified(m);
  bindPaths(m);
}

}  // namespace fastron::python
