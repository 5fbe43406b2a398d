#include "fastron/geometry/scene_file.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "fastron/geometry/mesh_loader.h"
#include "fastron/geometry/point_cloud.h"
#include "fastron/geometry/point_cloud_file.h"
#include "yaml_reader.h"

namespace fastron {
namespace {

using detail::jointState;
using detail::namingYamlErrors;
using detail::parseYaml;
using detail::Reader;

Shape readShape(const Reader& r, const YAML::Node& o, const std::string& what,
                const std::filesystem::path& base) {
  const std::string type = r.text(r.required(o, "shape", what), what + " shape");
  Shape shape = Sphere{1};
  if (type == "box") {
    shape = Box{r.vector3(r.required(o, "size", what), what + " size")};
  } else if (type == "sphere") {
    shape = Sphere{r.number(r.required(o, "radius", what), what + " radius")};
  } else if (type == "cylinder") {
    shape = Cylinder{r.number(r.required(o, "radius", what), what + " radius"),
                     r.number(r.required(o, "length", what), what + " length")};
  } else if (type == "capsule") {
    shape = Capsule{r.number(r.required(o, "radius", what), what + " radius"),
                    r.number(r.required(o, "length", what), what + " length")};
  } else if (type == "mesh") {
    const std::filesystem::path file = base / r.text(r.required(o, "file", what), what + " file");
    const Eigen::Vector3d scale =
        o["scale"] ? r.vector3(o["scale"], what + " scale") : Eigen::Vector3d::Ones();
    try {
      shape = Mesh{loadMesh(file, scale)};
    } catch (const FileError& e) {
      r.fail(o["file"], what + ": " + e.what());
    }
  } else {
    r.fail(o["shape"],
           what + ": unknown shape '" + type + "' (box, sphere, cylinder, capsule, mesh)");
  }
  try {
    validate(shape, what);
  } catch (const InvalidArgument& e) {
    r.fail(o, e.what());
  }
  return shape;
}

ObstacleMotion readMotion(const Reader& r, const YAML::Node& m, const std::string& what) {
  const std::string type = r.text(r.required(m, "type", what), what + " type");
  if (type == "random_walk") {
    r.onlyKeys(m, {"type", "step", "bounds", "seed"}, what);
    RandomWalk w;
    const auto step = r.numbers(r.required(m, "step", what), 2, what + " step [min, max]");
    w.minStep = step[0];
    w.maxStep = step[1];
    const YAML::Node bounds = r.required(m, "bounds", what);
    if (!bounds.IsSequence() || bounds.size() != 2)
      r.fail(bounds, what + " bounds must be [[min x, y, z], [max x, y, z]]");
    w.bounds = Eigen::AlignedBox3d(r.vector3(bounds[0], what + " bounds"),
                                   r.vector3(bounds[1], what + " bounds"));
    w.seed = m["seed"] ? r.count(m["seed"], what + " seed") : 1;
    return w;
  }
  if (type == "circle") {
    r.onlyKeys(m, {"type", "centre", "center", "radius", "axis", "period", "phase"}, what);
    CircularPath c;
    const YAML::Node centre = m["centre"] ? m["centre"] : m["center"];
    if (!centre) r.fail(m, what + " has no 'centre'");
    c.centre = r.vector3(centre, what + " centre");
    c.radius = r.number(r.required(m, "radius", what), what + " radius");
    if (m["axis"]) c.axis = r.vector3(m["axis"], what + " axis");
    c.period = r.number(r.required(m, "period", what), what + " period");
    if (m["phase"]) c.phase = r.number(m["phase"], what + " phase");
    return c;
  }
  if (type == "scripted") {
    r.onlyKeys(m, {"type", "keyframes"}, what);
    ScriptedPoses s;
    const YAML::Node keys = r.required(m, "keyframes", what);
    if (!keys.IsSequence() || keys.size() == 0)
      r.fail(keys, what + " keyframes must be a non-empty list");
    for (const auto& k : keys) {
      r.onlyKeys(k, {"time", "position", "rpy", "orientation"}, what + " keyframe");
      s.times.push_back(
          r.number(r.required(k, "time", what + " keyframe"), what + " keyframe time"));
      s.poses.push_back(r.pose(k, what + " keyframe"));
    }
    return s;
  }
  r.fail(m["type"], what + ": unknown motion type '" + type + "' (random_walk, circle, scripted)");
}

void readAllowedPairs(const Reader& r, const YAML::Node& pairs, Scene& scene) {
  if (!pairs.IsSequence()) r.fail(pairs, "allowed_collisions must be a list of [link, link] pairs");
  for (const auto& p : pairs) {
    if (!p.IsSequence() || p.size() != 2)
      r.fail(p, "allowed_collisions entries are [link, link] pairs");
    scene.allowedCollisions.allow(r.text(p[0], "allowed_collisions link"),
                                  r.text(p[1], "allowed_collisions link"));
  }
}

/// The sensed obstacles of a scene file: `point_clouds` and `octomaps`, each a list of
/// {id, file, radius, voxel, position, rpy | orientation}, files relative to the scene file.
void readSensedObstacles(const Reader& r, const YAML::Node& root, const std::filesystem::path& base,
                         Scene& scene) {
  for (const char* key : {"point_clouds", "octomaps"}) {
    const YAML::Node list = root[key];
    if (!list) continue;
    const bool octomap = std::string(key) == "octomaps";
    r.list(list, key);
    for (const auto& entry : list) {
      const std::string id = r.text(r.required(entry, "id", key), std::string(key) + " id");
      const std::string what = std::string(octomap ? "octomap" : "point cloud") + " '" + id + "'";
      r.onlyKeys(entry, {"id", "file", "radius", "voxel", "position", "rpy", "orientation"}, what);
      const std::filesystem::path file =
          base / r.text(r.required(entry, "file", what), what + " file");
      CloudFile cloud;
      try {
        cloud = readCloudFile(file);
      } catch (const FileError& e) {
        r.fail(entry["file"], what + ": " + e.what());
      }
      // An OctoMap's voxel is covered by the ball about its centre through its corners.
      const double radius = entry["radius"] ? r.number(entry["radius"], what + " radius")
                            : octomap
                                ? cloud.voxelSize * std::sqrt(3.0) / 2
                                : r.number(r.required(entry, "radius", what), what + " radius");
      const double voxel = entry["voxel"] ? r.number(entry["voxel"], what + " voxel")
                           : octomap      ? 0.0
                                          : radius;
      try {
        scene.add(
            {id, sensedCloud(cloud.points, radius, voxel), r.pose(entry, what), std::nullopt});
      } catch (const InvalidArgument& e) {
        r.fail(entry, what + ": " + e.what());
      }
    }
  }
}

Scene parseMoveItSceneText(const std::string& yaml, const std::string& source,
                           const std::filesystem::path& baseDirectory);

Scene parseSceneText(const std::string& yaml, const std::string& source,
                     const std::filesystem::path& baseDirectory) {
  const Reader r(source);
  const YAML::Node root = parseYaml(yaml, source);
  if (!root.IsMap()) throw FileError(source + ": a scene file is a YAML map");
  if (root["world"] && !root["obstacles"]) return parseMoveItSceneText(yaml, source, baseDirectory);
  r.onlyKeys(
      root,
      {"obstacles", "robot_base", "allowed_collisions", "description", "point_clouds", "octomaps"},
      "scene");
  Scene scene;
  if (root["robot_base"]) {
    r.onlyKeys(root["robot_base"], {"position", "rpy", "orientation"}, "robot_base");
    scene.robotBase = r.pose(root["robot_base"], "robot_base");
  }
  if (root["allowed_collisions"]) readAllowedPairs(r, root["allowed_collisions"], scene);
  const YAML::Node obstacles = root["obstacles"];
  if (!obstacles) {
    readSensedObstacles(r, root, baseDirectory, scene);
    return scene;
  }
  if (!obstacles.IsSequence()) r.fail(obstacles, "'obstacles' must be a list");
  std::size_t index = 0;
  for (const auto& o : obstacles) {
    const std::string name =
        o["name"] ? r.text(o["name"], "obstacle name") : "obstacle" + std::to_string(index);
    const std::string what = "obstacle '" + name + "'";
    r.onlyKeys(o,
               {"name", "shape", "size", "radius", "length", "file", "scale", "position", "rpy",
                "orientation", "motion"},
               what);
    Obstacle obstacle{name, readShape(r, o, what, baseDirectory), r.pose(o, what), std::nullopt};
    if (o["motion"]) obstacle.motion = readMotion(r, o["motion"], what + " motion");
    try {
      scene.add(std::move(obstacle));
    } catch (const InvalidArgument& e) {
      r.fail(o, e.what());
    }
    ++index;
  }
  readSensedObstacles(r, root, baseDirectory, scene);
  return scene;
}

/// A PlanningScene's robot_state: its joint_state, and the virtual joint's transform as the
/// robot's base.
void readRobotState(const Reader& r, const YAML::Node& state, Scene& scene) {
  if (const YAML::Node joints = state["joint_state"]; joints && joints["name"])
    scene.robotState = jointState(r, joints, "robot_state");
  const YAML::Node multi = state["multi_dof_joint_state"];
  if (!multi || !multi["transforms"]) return;
  const YAML::Node transforms =
      r.list(multi["transforms"], "robot_state.multi_dof_joint_state.transforms");
  if (transforms.size() == 0) return;
  if (transforms.size() > 1)
    r.fail(transforms,
           "robot_state.multi_dof_joint_state: one transform (the virtual joint's) is "
           "supported, found " +
               std::to_string(transforms.size()));
  const YAML::Node t = transforms[0];
  const std::string what = "robot_state.multi_dof_joint_state.transforms[0]";
  const auto q = r.numbers(r.required(t, "rotation", what), 4, what + " rotation [x, y, z, w]");
  const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
  if (rotation.norm() < 1e-9) r.fail(t, what + " rotation is a zero quaternion");
  scene.robotBase = Eigen::Isometry3d::Identity();
  scene.robotBase.linear() = rotation.normalized().toRotationMatrix();
  scene.robotBase.translation() =
      r.vector3(r.required(t, "translation", what), what + " translation");
}

using ObjectParts = std::vector<std::pair<Shape, Eigen::Isometry3d>>;

/// A MoveIt collision object's primitives (box, sphere, cylinder) with their world poses.
void readMoveItPrimitives(const Reader& r, const YAML::Node& object, const std::string& what,
                          const Eigen::Isometry3d& objectPose, ObjectParts& parts) {
  const YAML::Node primitives = object["primitives"];
  const YAML::Node poses = object["primitive_poses"];
  if (primitives) {
    r.list(primitives, what + " primitives");
    if (!poses) r.fail(object, what + ": one primitive_pose per primitive is needed");
    if (r.list(poses, what + " primitive_poses").size() != primitives.size())
      r.fail(poses, what + ": one primitive_pose per primitive is needed");
    for (std::size_t i = 0; i < primitives.size(); ++i) {
      const YAML::Node p = primitives[i];
      const std::string type =
          r.text(r.required(p, "type", what + " primitive"), what + " primitive type");
      const YAML::Node dims = r.required(p, "dimensions", what + " primitive");
      Shape shape = Sphere{1};
      if (type == "box") {
        shape = Box{r.vector3(dims, what + " box dimensions")};
      } else if (type == "sphere") {
        shape = Sphere{r.numbers(dims, 1, what + " sphere dimensions [radius]")[0]};
      } else if (type == "cylinder") {
        const auto d = r.numbers(dims, 2, what + " cylinder dimensions [height, radius]");
        shape = Cylinder{d[1], d[0]};
      } else {
        r.fail(p["type"],
               what + ": primitive type '" + type + "' is not supported (box, sphere, cylinder)");
      }
      parts.emplace_back(shape, objectPose * r.pose(poses[i], what + " primitive_pose"));
    }
  }
}

/// A MoveIt collision object's meshes (vertices and triangles inline) with their world poses.
void readMoveItMeshes(const Reader& r, const YAML::Node& object, const std::string& what,
                      const std::string& id, const std::string& source,
                      const Eigen::Isometry3d& objectPose, ObjectParts& parts) {
  if (const YAML::Node meshes = object["meshes"]) {
    r.list(meshes, what + " meshes");
    const YAML::Node meshPoses = object["mesh_poses"];
    if (!meshPoses) r.fail(object, what + ": one mesh_pose per mesh is needed");
    if (r.list(meshPoses, what + " mesh_poses").size() != meshes.size())
      r.fail(meshPoses, what + ": one mesh_pose per mesh is needed");
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      auto mesh = std::make_shared<TriangleMesh>();
      mesh->source = source + " (" + id + ")";
      for (const auto& v :
           r.list(r.required(meshes[i], "vertices", what + " mesh"), what + " mesh vertices"))
        mesh->vertices.push_back(r.vector3(v, what + " vertex"));
      for (const auto& t :
           r.list(r.required(meshes[i], "triangles", what + " mesh"), what + " mesh triangles")) {
        const auto idx =
            r.numbers(t["vertex_indices"] ? t["vertex_indices"] : t, 3, what + " triangle");
        for (const double k : idx) {
          if (k < 0 || k >= static_cast<double>(mesh->vertices.size()))
            r.fail(t, what + ": triangle vertex index out of range");
        }
        mesh->triangles.emplace_back(static_cast<int>(idx[0]), static_cast<int>(idx[1]),
                                     static_cast<int>(idx[2]));
      }
      parts.emplace_back(Mesh{mesh}, objectPose * r.pose(meshPoses[i], what + " mesh_pose"));
    }
  }
}

/// A MoveIt allowed_collision_matrix: the pairs whose entry is true may touch.
void readMoveItAllowedPairs(const Reader& r, const YAML::Node& acm, Scene& scene) {
  const YAML::Node names = r.list(r.required(acm, "entry_names", "allowed_collision_matrix"),
                                  "allowed_collision_matrix entry_names");
  const YAML::Node values = r.list(r.required(acm, "entry_values", "allowed_collision_matrix"),
                                   "allowed_collision_matrix entry_values");
  if (values.size() != names.size())
    r.fail(values, "allowed_collision_matrix: one row of entry_values per entry name");
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (!values[i].IsSequence() || values[i].size() != names.size())
      r.fail(values[i],
             "allowed_collision_matrix: row " + std::to_string(i) + " has the wrong length");
    for (std::size_t j = 0; j < names.size(); ++j) {
      if (r.flag(values[i][j], "allowed_collision_matrix entry"))
        scene.allowedCollisions.allow(r.text(names[i], "allowed_collision_matrix entry name"),
                                      r.text(names[j], "allowed_collision_matrix entry name"));
    }
  }
}

Scene parseMoveItSceneText(const std::string& yaml, const std::string& source,
                           const std::filesystem::path& baseDirectory) {
  const Reader r(source);
  const YAML::Node root = parseYaml(yaml, source);
  Scene scene;
  const YAML::Node world = root["world"];
  if (!world || !world.IsMap()) r.fail(root, "not a MoveIt PlanningScene: no 'world' map");
  const YAML::Node objects = world["collision_objects"];
  if (objects && !objects.IsSequence()) r.fail(objects, "world.collision_objects must be a list");
  for (const auto& object : objects) {
    const std::string id =
        r.text(r.required(object, "id", "a collision object"), "collision object id");
    const std::string what = "collision object '" + id + "'";
    const Eigen::Isometry3d objectPose =
        object["pose"] ? r.pose(object["pose"], what + " pose") : Eigen::Isometry3d::Identity();
    ObjectParts parts;
    readMoveItPrimitives(r, object, what, objectPose, parts);
    readMoveItMeshes(r, object, what, id, source, objectPose, parts);
    if (parts.empty()) r.fail(object, what + " has no primitives or meshes");
    for (std::size_t i = 0; i < parts.size(); ++i) {
      try {
        scene.add({parts.size() == 1 ? id : id + "/" + std::to_string(i), parts[i].first,
                   parts[i].second, std::nullopt});
      } catch (const InvalidArgument& e) {
        r.fail(object, e.what());
      }
    }
  }
  if (const YAML::Node state = root["robot_state"]) readRobotState(r, state, scene);
  if (const YAML::Node acm = root["allowed_collision_matrix"])
    readMoveItAllowedPairs(r, acm, scene);
  readSensedObstacles(r, root, baseDirectory, scene);
  return scene;
}

}  // namespace

Scene parseScene(const std::string& yaml, const std::string& source,
                 const std::filesystem::path& baseDirectory) {
  return namingYamlErrors(source, [&] { return parseSceneText(yaml, source, baseDirectory); });
}

Scene parseMoveItScene(const std::string& yaml, const std::string& source,
                       const std::filesystem::path& baseDirectory) {
  return namingYamlErrors(source,
                          [&] { return parseMoveItSceneText(yaml, source, baseDirectory); });
}

Scene loadScene(const std::filesystem::path& path) {
  return parseScene(readFile(path, "scene file"), path.string(), path.parent_path());
}

}  // namespace fastron
