// Robots (URDF, SRDF, forward kinematics), scenes (our YAML, MoveIt files, moving obstacles) and
// the exact checkers (FCL, GJK).

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.h"
#include "bindings.h"
#include "fastron/core/error.h"
#include "fastron/core/model_file.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/moveit_request.h"
#include "fastron/geometry/point_cloud.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/pipeline/self_pair_tables.h"

namespace fastron::python {

namespace {

/// The `name` of each item (links, obstacles), in order.
template <class Items>
std::vector<std::string> namesOf(const Items& items) {
  std::vector<std::string> names;
  for (const auto& item : items) names.push_back(item.name);
  return names;
}

/// World positions of every link's origin: (links, 3) for one configuration, (n, links, 3) for
/// each row of (n, d).
py::array_t<double> linkPositions(const Robot& robot, py::handle q) {
  const ConfigurationRows rows = configurations(q, robot.dof(), "q");
  const std::size_t links = robot.links().size();
  py::array_t<double> out(rows.single
                              ? std::vector<py::ssize_t>{static_cast<py::ssize_t>(links), 3}
                              : std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows.rows),
                                                         static_cast<py::ssize_t>(links), 3});
  double* data = out.mutable_data();
  py::gil_scoped_release released;
  KinematicsData scratch = makeKinematicsData(robot);
  for (std::size_t i = 0; i < rows.rows; ++i) {
    forwardKinematics(robot, rows.data + i * rows.cols, scratch);
    for (std::size_t l = 0; l < links; ++l) {
      const Eigen::Vector3d p = scratch.linkPoses[l].translation();
      std::copy(p.data(), p.data() + 3, data + (i * links + l) * 3);
    }
  }
  return out;
}

Eigen::Isometry3d pose(py::handle position, py::handle rpy) {
  return makePose(vector(position, 3, "position"),
                  rpy.is_none() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(vector(rpy, 3, "rpy")));
}

void addObstacle(Scene& scene, const std::string& name, Shape shape, py::handle position,
                 py::handle rpy) {
  scene.add(Obstacle{name, std::move(shape), pose(position, rpy), std::nullopt});
}

/// The checker options of the bindings' keywords; with `selfPairTables`, the robot's tables from
/// the cache (pipeline::selfPairTables, as `fastron plan` reads them), a warning when they cannot
/// be kept there.
CheckerOptions checkerOptions(const Robot& robot, bool selfCollision, double padding,
                              bool proveMotionsFree, bool selfPairTables) {
  CheckerOptions options{
      .selfCollision = selfCollision, .padding = padding, .proveMotionsFree = proveMotionsFree};
  if (!(selfPairTables && selfCollision && proveMotionsFree)) return options;
  pipeline::SelfPairTables tables;
  {
    py::gil_scoped_release released;
    tables = pipeline::selfPairTables(robot, {.padding = padding});
  }
  if (!tables.warning.empty()) PyErr_WarnEx(PyExc_RuntimeWarning, tables.warning.c_str(), 1);
  options.selfPairTables = tables.tables;
  return options;
}

template <class Checker>
std::shared_ptr<Checker> makeChecker(const Robot& robot, const Scene& scene, bool selfCollision,
                                     double padding, bool proveMotionsFree, bool selfPairTables) {
  return std::make_shared<Checker>(
      robot, scene,
      checkerOptions(robot, selfCollision, padding, proveMotionsFree, selfPairTables));
}

py::object contactObject(const std::optional<Contact>& contact) {
  if (!contact) return py::none();
  return py::cast(*contact);
}

/// Robot, and loading robots (shipped, URDF, with an SRDF).
void bindRobots(py::module_& m) {
  py::class_<Robot>(m, "Robot", "A robot from a URDF: kinematic tree, collision shapes, limits.")
      .def_property_readonly("name", &Robot::name)
      .def_property_readonly("dof", &Robot::dof, "Actuated joints (values per configuration).")
      .def_property_readonly("joint_names", &Robot::actuatedJointNames,
                             "The actuated joints, in configuration order.")
      .def_property_readonly("link_names",
                             [](const Robot& robot) { return namesOf(robot.links()); })
      .def_property_readonly("limits", &Robot::limits)
      .def("link_positions", &linkPositions, py::arg("q"),
           "Forward kinematics: the world position of every link's origin (link_names order), "
           "shape (links, 3) for one configuration (d,), (n, links, 3) for (n, d).")
      .def("__repr__", [](const Robot& robot) {
        return "Robot('" + robot.name() + "', dof=" + std::to_string(robot.dof()) + ")";
      });
  const auto description = [](const std::string& nameOrPath,
                              const std::optional<std::filesystem::path>& srdf,
                              const std::vector<std::filesystem::path>& packagePaths,
                              const std::optional<std::string>& group) {
    UrdfOptions options;
    options.searchPaths = packagePaths;
    RobotDescription d =
        loadRobotDescription(nameOrPath, options, srdf.value_or(std::filesystem::path()));
    if (group) d.robot.setActuatedJoints(d.srdf.group(*group).joints);
    return d;
  };
  m.def(
      "load_robot",
      [description](const std::string& nameOrPath, const std::optional<std::filesystem::path>& srdf,
                    const std::vector<std::filesystem::path>& packagePaths,
                    const std::optional<std::string>& group) {
        return description(nameOrPath, srdf, packagePaths, group).robot;
      },
      py::arg("name_or_path"), py::kw_only(), py::arg("srdf") = py::none(),
      py::arg("package_paths") = std::vector<std::filesystem::path>{},
      py::arg("group") = py::none(),
      "A shipped robot by name (see shipped_robots) or a URDF file; `srdf` adds a MoveIt SRDF's "
      "disabled collisions and groups; `group` actuates an SRDF group's joints; `package_paths` "
      "are where package:// meshes are looked up.");
  m.def(
      "load_robot_description",
      [description](const std::string& nameOrPath, const std::optional<std::filesystem::path>& srdf,
                    const std::vector<std::filesystem::path>& packagePaths,
                    const std::optional<std::string>& group) {
        const RobotDescription d = description(nameOrPath, srdf, packagePaths, group);
        py::dict groups;
        for (const SrdfGroup& g : d.srdf.groups) groups[py::str(g.name)] = g.joints;
        return py::make_tuple(d.robot, groups, d.warnings);
      },
      py::arg("name_or_path"), py::kw_only(), py::arg("srdf") = py::none(),
      py::arg("package_paths") = std::vector<std::filesystem::path>{},
      py::arg("group") = py::none(),
      "As load_robot, with what its SRDFs say: (robot, groups: {name: [joints]}, warnings: "
      "[str], one per link or joint the SRDF names and the URDF lacks, skipped as MoveIt does).");
  m.def(
      "shipped_robots", [] { return namesOf(shippedRobots()); },
      "Names of the robots shipped with Fastron.");
  m.def("data_directory", &dataDirectory,
        "The data folder (robots/, scenes/): $FASTRON_DATA_DIR, else the installation's.");
}

/// A cloud obstacle from an (n, 3) array, down-sampled at `voxel` (default: the radius).
PointCloud cloudOf(py::handle points, double radius, std::optional<double> voxel,
                   const std::string& name) {
  const ConfigurationRows rows = configurations(points, 3, "points", false);
  // Rows of three doubles, C-ordered: Eigen::Vector3d's layout.
  const std::span<const Eigen::Vector3d> view(reinterpret_cast<const Eigen::Vector3d*>(rows.data),
                                              rows.rows);
  return sensedCloud(view, radius, voxel.value_or(radius), "array '" + name + "'");
}

/// Scene, scene files, MoveIt requests and the robot a request plans.
void bindScenes(py::module_& m) {
  py::class_<Scene>(m, "Scene", "Obstacles (some moving) and where the robot's base is.")
      .def(py::init<>())
      .def_property_readonly("obstacle_names",
                             [](const Scene& scene) { return namesOf(scene.obstacles()); })
      .def("__len__", &Scene::size)
      .def_property_readonly("time", &Scene::time)
      .def("step", &Scene::step, py::arg("steps") = 1,
           "Moves every obstacle that has a motion by `steps` time steps.")
      .def(
          "add_box",
          [](Scene& s, const std::string& name, py::handle size, py::handle position,
             py::handle rpy) { addObstacle(s, name, Box{vector(size, 3, "size")}, position, rpy); },
          py::arg("name"), py::arg("size"), py::arg("position"), py::arg("rpy") = py::none())
      .def(
          "add_sphere",
          [](Scene& s, const std::string& name, double radius, py::handle position) {
            addObstacle(s, name, Sphere{radius}, position, py::none());
          },
          py::arg("name"), py::arg("radius"), py::arg("position"))
      .def(
          "add_cylinder",
          [](Scene& s, const std::string& name, double radius, double length, py::handle position,
             py::handle rpy) {
            addObstacle(s, name, Cylinder{radius, length}, position, rpy);
          },
          py::arg("name"), py::arg("radius"), py::arg("length"), py::arg("position"),
          py::arg("rpy") = py::none())
      .def(
          "add_point_cloud",
          [](Scene& s, const std::string& name, py::handle points, double radius,
             std::optional<double> voxel, py::handle position, py::handle rpy) {
            s.add({name, cloudOf(points, radius, voxel, name),
                   position.is_none() ? Eigen::Isometry3d::Identity() : pose(position, rpy),
                   std::nullopt});
          },
          py::arg("name"), py::arg("points"), py::arg("radius"), py::kw_only(),
          py::arg("voxel") = py::none(), py::arg("position") = py::none(),
          py::arg("rpy") = py::none(),
          "A sensed obstacle: a ball of `radius` about each row of `points` ((n, 3), metres; "
          "n may be 0), down-sampled to one point per cube of edge `voxel` (default: the "
          "radius; 0 keeps every point). A float64 C-ordered array is read in place. "
          "`position`/`rpy` pose the cloud's frame (default: the world's).")
      .def(
          "set_point_cloud",
          [](Scene& s, const std::string& name, py::handle points, double radius,
             std::optional<double> voxel) {
            s.setShape(name, cloudOf(points, radius, voxel, name));
          },
          py::arg("name"), py::arg("points"), py::arg("radius"), py::kw_only(),
          py::arg("voxel") = py::none(),
          "Replaces a cloud's points (the next camera frame), its pose kept; as add_point_cloud.")
      .def("remove", &Scene::remove, py::arg("name"))
      .def(
          "set_pose",
          [](Scene& s, const std::string& name, py::handle position, py::handle rpy) {
            s.setPose(name, pose(position, rpy));
          },
          py::arg("name"), py::arg("position"), py::arg("rpy") = py::none(),
          "Moves an obstacle; rpy: roll, pitch, yaw about fixed x, y, z (radians).")
      .def(
          "position",
          [](const Scene& s, const std::string& name) {
            return toArray(s.obstacle(name).pose.translation());
          },
          py::arg("name"))
      .def("grown", &Scene::grown, py::arg("margin"),
           "The same scene with every obstacle but meshes grown by `margin` metres.")
      .def("__repr__", [](const Scene& scene) {
        return "Scene(" + std::to_string(scene.size()) + " obstacles)";
      });
  m.def("load_scene", &loadScene, py::arg("path"),
        "A scene file: Fastron's YAML (top-level `obstacles`) or a MoveIt PlanningScene.");
  m.def(
      "load_moveit_request",
      [](const std::filesystem::path& path, const Robot& robot) {
        const PlanRequest request = loadMoveItRequest(path);
        return py::make_tuple(toArray(actuatedConfiguration(robot, request.start, "start")),
                              toArray(actuatedConfiguration(robot, request.goal, "goal")));
      },
      py::arg("path"), py::arg("robot"),
      "A MoveIt MotionPlanRequest as (start, goal) configurations of the robot's actuated joints.");
  m.def(
      "robot_for_request",
      [](const Robot& robot, const std::filesystem::path& request, const Scene& scene,
         const std::map<std::string, std::vector<std::string>>& groups) {
        std::vector<SrdfGroup> srdfGroups;
        for (const auto& [name, joints] : groups) srdfGroups.push_back({name, joints});
        const PlanRequest r = loadMoveItRequest(request);
        RequestRobot planned = robotForRequest(robot, srdfGroups, scene, r, request.string());
        const RequestEnds ends = requestEnds(planned.robot, r, request.string());
        return py::make_tuple(planned.robot, toArray(ends.start), toArray(ends.goal),
                              planned.warning);
      },
      py::arg("robot"), py::arg("request"), py::arg("scene"),
      py::arg("groups") = std::map<std::string, std::vector<std::string>>{},
      "A MoveIt request as MoveIt plans it: (robot, start, goal, warning), the robot with the "
      "request's group actuated (from `groups`, as load_robot_description gives them) and its "
      "other joints held where the scene's robot_state and the request's start state put them; "
      "values within 0.05 of a limit clamped; warning says when the group is not in `groups`.");
}

/// robot_features and load_model: what needs a robot in core's terms.
void bindFeaturesAndModels(py::module_& m) {
  m.def(
      "robot_features",
      [](const Robot& robot, const std::string& kind, const std::vector<std::string>& points,
         std::size_t maxPoints, double minSpacing, std::size_t maxPerBody, const std::string& rule,
         bool alongGeometry) {
        const FeatureKind parsed = parseFeatureKind(kind);
        if (parsed == FeatureKind::JointScaling) return robotFeatures(robot, parsed);
        if (rule != "spread" && rule != "cover")
          throw InvalidArgument("control point rule must be 'spread' or 'cover', got '" + rule +
                                "'");
        const ControlPointOptions options{
            .rule = rule == "cover" ? ControlPointRule::Cover : ControlPointRule::Spread,
            .maxPoints = maxPoints,
            .minSpacing = minSpacing,
            .maxPerBody = maxPerBody,
            .alongGeometry = alongGeometry};
        return robotFeatures(robot, parsed,
                             points.empty() ? defaultControlPoints(robot, options)
                                            : namedControlPoints(robot, points));
      },
      py::arg("robot"), py::arg("kind") = "fk",
      py::arg("control_points") = std::vector<std::string>{}, py::kw_only(),
      py::arg("max_points") = ControlPointOptions{}.maxPoints,
      py::arg("min_spacing") = ControlPointOptions{}.minSpacing,
      py::arg("max_per_body") = ControlPointOptions{}.maxPerBody, py::arg("rule") = "spread",
      py::arg("along_geometry") = false,
      "The features a model of `robot` learns on: 'fk' (world positions of control points: "
      "'LINK' or 'LINK@X:Y:Z'; default: chosen automatically, at most max_points of them, "
      "min_spacing metres apart on average, max_per_body on one rigid body; 0 = no limit; rule "
      "'spread' (the points that move most) or 'cover' (spread along the chain); "
      "along_geometry: also candidates along each link's collision geometry) or "
      "'joints' (joint scaling).");
  m.def(
      "load_model",
      [](const std::filesystem::path& path, const std::optional<Robot>& robot) {
        return std::make_shared<Model>(robot ? loadModelFor(path, *robot) : loadModel(path));
      },
      py::arg("path"), py::arg("robot") = py::none(),
      "Reads a model file; a task-space ('fk') model needs the robot it was trained for.");
}

/// Contact, what a scene checker's first_contact names.
void bindContact(py::module_& m) {
  py::class_<Contact>(m, "Contact", "What collided.")
      .def_readonly("robot_link", &Contact::robotLink)
      .def_readonly("other", &Contact::other, "An obstacle, or a link for a self-collision.")
      .def_readonly("self_collision", &Contact::selfCollision)
      .def("__repr__", [](const Contact& c) {
        return "Contact('" + c.robotLink + "', '" + c.other + "'" +
               (c.selfCollision ? ", self_collision=True)" : ")");
      });
}

}  // namespace

void bindGeometry(py::module_& m) {
  bindRobots(m);
  bindScenes(m);
  bindFeaturesAndModels(m);
  bindContact(m);
}

void bindSceneCheckers(py::module_& m) {
  py::class_<SceneChecker, CollisionChecker, std::shared_ptr<SceneChecker>>(
      m, "SceneChecker",
      "A robot checked exactly against a scene (FclChecker, GjkChecker, or scene_checker(name)).")
      .def_property_readonly("robot", &SceneChecker::robot)
      .def("set_scene", &SceneChecker::setScene, py::arg("scene"),
           "Takes the obstacles' new poses; safe while other threads check.")
      .def(
          "first_contact",
          [](const SceneChecker& checker, py::handle q) {
            const Eigen::VectorXd v = vector(q, checker.dof(), "q");
            return contactObject(checker.firstContact({v.data(), checker.dof()}));
          },
          py::arg("q"), "The first contact found at q, or None when q is free.")
      .def_property_readonly("measures_distance", &SceneChecker::measuresDistance,
                             "True when distance() answers (FCL; not GJK).")
      .def(
          "distance",
          [](const SceneChecker& checker, py::handle q) {
            const Eigen::VectorXd v = vector(q, checker.dof(), "q");
            return checker.distance({v.data(), checker.dof()});
          },
          py::arg("q"),
          "Smallest distance between the robot and any obstacle (0 in collision); raises "
          "Unsupported when measures_distance is False.");

  py::class_<FclChecker, SceneChecker, std::shared_ptr<FclChecker>>(
      m, "FclChecker", "The exact checker: forward kinematics, then FCL against the scene.")
      .def(py::init(&makeChecker<FclChecker>), py::arg("robot"), py::arg("scene"), py::kw_only(),
           py::arg("self_collision") = false, py::arg("padding") = 0.0,
           py::arg("prove_motions_free") = true, py::arg("self_pair_tables") = false,
           "self_pair_tables: with self_collision on a robot of meshes, its self pairs that one "
           "or two joints turn are read from tables of their distance, built once per robot "
           "and kept in the cache ($FASTRON_CACHE_DIR, else ~/.cache/fastron), as `fastron "
           "plan` does: the same answers, faster (docs/geometry.md).")
      .def_property_readonly("self_pair_table_count", &FclChecker::selfPairTableCount,
                             "Self pairs read from a table of their distance.");

  py::class_<GjkChecker, SceneChecker, std::shared_ptr<GjkChecker>>(
      m, "GjkChecker", "Forward kinematics, then libccd's GJK on convex shapes.")
      .def(py::init([](const Robot& robot, const Scene& scene, bool selfCollision, double padding) {
             return makeChecker<GjkChecker>(robot, scene, selfCollision, padding, false, false);
           }),
           py::arg("robot"), py::arg("scene"), py::kw_only(), py::arg("self_collision") = false,
           py::arg("padding") = 0.0);

  m.def(
      "scene_checker_names",
      [] {
        std::vector<std::string> names;
        for (const SceneCheckerKind& kind : sceneCheckerKinds()) names.push_back(kind.name);
        return names;
      },
      "The exact checkers' names, the default ('fcl') first.");
  m.def(
      "scene_checker",
      [](const std::string& name, const Robot& robot, const Scene& scene, bool selfCollision,
         double padding, bool proveMotionsFree, bool selfPairTables) {
        return makeSceneChecker(
            name, robot, scene,
            checkerOptions(robot, selfCollision, padding, proveMotionsFree, selfPairTables));
      },
      py::arg("name"), py::arg("robot"), py::arg("scene"), py::kw_only(),
      py::arg("self_collision") = false, py::arg("padding") = 0.0,
      py::arg("prove_motions_free") = true, py::arg("self_pair_tables") = false,
      "The exact checker `name` (scene_checker_names()) on `robot` in `scene`, as the command "
      "line's --checker builds it; self_pair_tables as FclChecker's (`fastron plan` turns them "
      "on with --self-collision).");
}

}  // namespace fastron::python
