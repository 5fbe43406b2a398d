#pragma once
// Scene files: the project's own YAML (docs/geometry.md, "Scenes") and MoveIt's PlanningScene and
// MotionPlanRequest YAML, the format of public planning benchmarks.

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/scene.h"

namespace FASTRON_API fastron {

/// Reads a scene file: the project's format (a top-level `obstacles` list) or a MoveIt
/// PlanningScene (a top-level `world`). Throws FileError naming the file and line.
Scene loadScene(const std::filesystem::path& path);

/// The project's scene format from a string; mesh files are resolved from `baseDirectory`.
Scene parseScene(const std::string& yaml, const std::string& source,
                 const std::filesystem::path& baseDirectory = {});

/// A MoveIt PlanningScene: world.collision_objects (primitives box / sphere / cylinder with
/// primitive_poses, optional object pose, inline meshes) and allowed_collision_matrix.
Scene parseMoveItScene(const std::string& yaml, const std::string& source);

/// Joint positions by name (a MoveIt joint_state, or joint_constraints).
struct NamedPositions {
  std::vector<std::string> names;
  std::vector<double> positions;
};

/// A MoveIt MotionPlanRequest: start_state.joint_state and goal_constraints[0].joint_constraints.
struct PlanRequest {
  std::string group;
  NamedPositions start, goal;
};
PlanRequest loadMoveItRequest(const std::filesystem::path& path);
/// A MotionPlanRequest from a string; errors name `source` and the line.
PlanRequest parseMoveItRequest(const std::string& yaml, const std::string& source);

/// The robot's actuated joints taken from `positions` (extra names are ignored). Throws
/// InvalidArgument naming the first actuated joint that is missing or out of its limits.
std::vector<double> actuatedConfiguration(const Robot& robot, const NamedPositions& positions,
                                          const std::string& what);

/// A request's start and goal as configurations of `robot` (actuatedConfiguration of each);
/// errors name `source` and which end.
struct RequestEnds {
  Eigen::VectorXd start, goal;
};
RequestEnds requestEnds(const Robot& robot, const PlanRequest& request, const std::string& source);

}  // namespace fastron
