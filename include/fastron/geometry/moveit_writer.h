#pragma once
// Writing MoveIt PlanningScene and MotionPlanRequest YAML, the format scene_file.h and
// moveit_request.h read: planning problems made here can be planned by `fastron bench
// motion-bench` and by MoveIt itself.

#include <string>

#include "fastron/core/export.h"
#include "fastron/geometry/moveit_request.h"
#include "fastron/geometry/scene.h"
#include "fastron/geometry/scene_file.h"

namespace FASTRON_API fastron {

/// The obstacles of `scene`, at their current poses, as a PlanningScene's world.collision_objects,
/// one object per obstacle (its name as the id) holding one primitive: box, sphere or cylinder.
/// Throws InvalidArgument naming the obstacle for a capsule or a mesh (not among MoveIt's
/// primitives here), and for a robot base other than the identity (MoveIt places the robot through
/// its own model).
std::string moveItSceneYaml(const Scene& scene, const std::string& robotName);

/// A MotionPlanRequest for `group` with the start under start_state.joint_state and the goal as
/// goal_constraints[0].joint_constraints. Throws InvalidArgument when a joint list's names and
/// positions differ in length or a position is not finite.
std::string moveItRequestYaml(const PlanRequest& request);

}  // namespace fastron
