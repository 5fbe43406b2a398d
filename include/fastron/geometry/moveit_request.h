#pragma once
// MoveIt MotionPlanRequest YAML (start state, joint goal, group), and the robot and configurations
// a request plans, read as MoveIt reads them (its bounds margin, continuous joints, the group's
// joints actuated and the others held where the scene's robot state puts them).

#include <filesystem>
#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/scene.h"
#include "fastron/geometry/srdf.h"

namespace FASTRON_API fastron {

/// A MoveIt MotionPlanRequest: start_state.joint_state and goal_constraints[0].joint_constraints.
struct PlanRequest {
  std::string group;
  NamedPositions start, goal;
};
PlanRequest loadMoveItRequest(const std::filesystem::path& path);
/// A MotionPlanRequest from a string; errors name `source` and the line.
PlanRequest parseMoveItRequest(const std::string& yaml, const std::string& source);

/// How far a joint value may lie beyond its limits and still be taken (clamped onto them): MoveIt's
/// bounds margin for start states (FixStartStateBounds' start_state_max_bounds_error, 0.05 rad or
/// m by default). Problem files hold values such as ±3.141592653589793 for limits of ±3.14159.
inline constexpr double kJointBoundsMargin = 0.05;

/// `value` for `joint` as MoveIt takes it: a continuous joint's wrapped into [-pi, pi]; a value
/// within kJointBoundsMargin beyond a limit clamped onto it. Throws InvalidArgument naming
/// `what`, the joint, the value and the limits when it lies farther out or is not finite.
double jointValueWithinLimits(const Joint& joint, double value, const std::string& what);

/// The robot's actuated joints taken from `positions` (extra names are ignored), each through
/// jointValueWithinLimits. Throws InvalidArgument naming the first actuated joint that is
/// missing or out of its limits.
std::vector<double> actuatedConfiguration(const Robot& robot, const NamedPositions& positions,
                                          const std::string& what);

/// A request's start and goal as configurations of `robot` (actuatedConfiguration of each);
/// errors name `source` and which end.
struct RequestEnds {
  Eigen::VectorXd start, goal;
};
RequestEnds requestEnds(const Robot& robot, const PlanRequest& request, const std::string& source);

/// `robot` as MoveIt plans a request in a scene: the joints of the request's group (an SRDF
/// group) actuated, and every other movable joint that the scene's robot state or, over it, the
/// request's start state names held there (jointValueWithinLimits; names the robot lacks or
/// holds fixed are ignored). A request without a group, or whose group `groups` does not have,
/// keeps the robot's actuated joints (`warning` says so when `groups` has groups at all). Throws
/// InvalidArgument naming `source` and the joint at fault.
struct RequestRobot {
  Robot robot;
  std::string warning;  ///< empty, or why the request's group was not applied
};
RequestRobot robotForRequest(Robot robot, const std::vector<SrdfGroup>& groups, const Scene& scene,
                             const PlanRequest& request, const std::string& source);

}  // namespace fastron
