#include "fastron/geometry/moveit_writer.h"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>

#include "fastron/core/error.h"
#include "fastron/geometry/moveit_request.h"
#include "overloaded.h"

namespace fastron {
namespace {

// The shortest text that reads back as the same double (0.7, not 0.69999999999999996).
std::string shortest(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return {text, end};
}

void emitNumbers(YAML::Emitter& out, std::initializer_list<double> values) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const double v : values) out << shortest(v);
  out << YAML::EndSeq;
}

void emitPose(YAML::Emitter& out, const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d& p = pose.translation();
  out << YAML::BeginMap << YAML::Key << "position";
  emitNumbers(out, {p.x(), p.y(), p.z()});
  out << YAML::Key << "orientation";
  emitNumbers(out, {q.x(), q.y(), q.z(), q.w()});
  out << YAML::EndMap;
}

void emitPrimitive(YAML::Emitter& out, const Obstacle& obstacle) {
  out << YAML::BeginMap;
  std::visit(
      Overloaded{
          [&](const Box& b) {
            out << YAML::Key << "type" << YAML::Value << "box" << YAML::Key << "dimensions";
            emitNumbers(out, {b.size.x(), b.size.y(), b.size.z()});
          },
          [&](const Sphere& s) {
            out << YAML::Key << "type" << YAML::Value << "sphere" << YAML::Key << "dimensions";
            emitNumbers(out, {s.radius});
          },
          [&](const Cylinder& c) {
            out << YAML::Key << "type" << YAML::Value << "cylinder" << YAML::Key << "dimensions";
            emitNumbers(out, {c.length, c.radius});  // MoveIt: [height, radius]
          },
          [&](const Capsule&) {
            throw InvalidArgument("MoveIt scene: obstacle '" + obstacle.name +
                                  "' is a capsule, which is not a MoveIt primitive");
          },
          [&](const Mesh&) {
            throw InvalidArgument("MoveIt scene: obstacle '" + obstacle.name +
                                  "' is a mesh; only primitives are written");
          },
          [&](const PointCloud&) {
            throw InvalidArgument("MoveIt scene: obstacle '" + obstacle.name +
                                  "' is a point cloud; only primitives are written");
          },
      },
      obstacle.shape);
  out << YAML::EndMap;
}

void checkJoints(const NamedPositions& joints, const std::string& what) {
  if (joints.names.size() != joints.positions.size()) {
    throw InvalidArgument("MoveIt request: " + what + " has " +
                          std::to_string(joints.names.size()) + " joint names but " +
                          std::to_string(joints.positions.size()) + " positions");
  }
  for (std::size_t i = 0; i < joints.positions.size(); ++i) {
    if (!std::isfinite(joints.positions[i])) {
      throw InvalidArgument("MoveIt request: " + what + " position of '" + joints.names[i] +
                            "' is not finite");
    }
  }
}

}  // namespace

std::string moveItSceneYaml(const Scene& scene, const std::string& robotName) {
  if (!scene.robotBase.isApprox(Eigen::Isometry3d::Identity())) {
    throw InvalidArgument(
        "MoveIt scene: the robot base must be the identity (MoveIt places the "
        "robot through its own model)");
  }
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << "" << YAML::Key
      << "robot_model_name" << YAML::Value << robotName << YAML::Key << "world" << YAML::Value
      << YAML::BeginMap << YAML::Key << "collision_objects" << YAML::Value << YAML::BeginSeq;
  for (const Obstacle& o : scene.obstacles()) {
    out << YAML::BeginMap << YAML::Key << "id" << YAML::Value << o.name << YAML::Key << "primitives"
        << YAML::Value << YAML::BeginSeq;
    emitPrimitive(out, o);
    out << YAML::EndSeq << YAML::Key << "primitive_poses" << YAML::Value << YAML::BeginSeq;
    emitPose(out, o.pose);
    out << YAML::EndSeq << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string moveItRequestYaml(const PlanRequest& request) {
  checkJoints(request.start, "start");
  checkJoints(request.goal, "goal");
  YAML::Emitter out;
  out << YAML::BeginMap << YAML::Key << "group_name" << YAML::Value << request.group << YAML::Key
      << "start_state" << YAML::Value << YAML::BeginMap << YAML::Key << "joint_state" << YAML::Value
      << YAML::BeginMap << YAML::Key << "name" << YAML::Value << YAML::Flow << request.start.names
      << YAML::Key << "position" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const double position : request.start.positions) out << shortest(position);
  out << YAML::EndSeq << YAML::EndMap << YAML::EndMap;
  out << YAML::Key << "goal_constraints" << YAML::Value << YAML::BeginSeq << YAML::BeginMap
      << YAML::Key << "joint_constraints" << YAML::Value << YAML::BeginSeq;
  for (std::size_t i = 0; i < request.goal.names.size(); ++i) {
    out << YAML::BeginMap << YAML::Key << "joint_name" << YAML::Value << request.goal.names[i]
        << YAML::Key << "position" << YAML::Value << shortest(request.goal.positions[i])
        << YAML::Key << "tolerance_above" << YAML::Value << 0.0001 << YAML::Key << "tolerance_below"
        << YAML::Value << 0.0001 << YAML::Key << "weight" << YAML::Value << 1.0 << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace fastron
