#pragma once
// Scene files: the project's own YAML (docs/geometry.md, "Scenes") and MoveIt's PlanningScene YAML,
// the format of public planning benchmarks (their requests: moveit_request.h).

#include <filesystem>
#include <string>

#include "fastron/core/export.h"
#include "fastron/geometry/scene.h"

namespace FASTRON_API fastron {

/// Reads a scene file: the project's format (a top-level `obstacles` list) or a MoveIt
/// PlanningScene (a top-level `world`). Throws FileError naming the file and line.
Scene loadScene(const std::filesystem::path& path);

/// The project's scene format from a string; mesh and cloud files are resolved from
/// `baseDirectory`. Both formats take the top-level lists `point_clouds` and `octomaps`
/// ({id, file, radius, voxel, position, rpy | orientation}; docs/geometry.md).
Scene parseScene(const std::string& yaml, const std::string& source,
                 const std::filesystem::path& baseDirectory = {});

/// A MoveIt PlanningScene: world.collision_objects (primitives box / sphere / cylinder with
/// primitive_poses, optional object pose, inline meshes), allowed_collision_matrix, and
/// robot_state (joint_state as Scene::robotState; a multi_dof_joint_state's one transform, the
/// virtual joint's, as Scene::robotBase).
Scene parseMoveItScene(const std::string& yaml, const std::string& source,
                       const std::filesystem::path& baseDirectory = {});

}  // namespace fastron
