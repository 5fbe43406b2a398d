#include "fastron/geometry/moveit_request.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "yaml_reader.h"

namespace fastron {
namespace {

using detail::jointState;
using detail::namingYamlErrors;
using detail::parseYaml;
using detail::Reader;

PlanRequest parseRequestText(const std::string& yaml, const std::string& source) {
  const Reader r(source);
  const YAML::Node root = parseYaml(yaml, source);
  PlanRequest request;
  if (root["group_name"]) request.group = r.text(root["group_name"], "group_name");
  request.start = jointState(
      r, r.required(r.required(root, "start_state", "the request"), "joint_state", "start_state"),
      "start_state");
  const YAML::Node goals = r.required(root, "goal_constraints", "the request");
  if (!goals.IsSequence() || goals.size() == 0)
    r.fail(goals, "goal_constraints must be a non-empty list");
  const YAML::Node joints = r.list(r.required(goals[0], "joint_constraints", "goal_constraints[0]"),
                                   "goal_constraints[0].joint_constraints");
  for (const auto& c : joints) {
    request.goal.names.push_back(
        r.text(r.required(c, "joint_name", "a joint constraint"), "joint_name"));
    request.goal.positions.push_back(r.number(r.required(c, "position", "a joint constraint"),
                                              "goal position of " + request.goal.names.back()));
  }
  return request;
}

}  // namespace

PlanRequest parseMoveItRequest(const std::string& yaml, const std::string& source) {
  return namingYamlErrors(source, [&] { return parseRequestText(yaml, source); });
}

PlanRequest loadMoveItRequest(const std::filesystem::path& path) {
  return parseMoveItRequest(readFile(path, "motion plan request"), path.string());
}

double jointValueWithinLimits(const Joint& joint, double value, const std::string& what) {
  const auto fail = [&](const std::string& why) {
    throw InvalidArgument(what + ": joint '" + joint.name + "' at " + std::to_string(value) + why);
  };
  if (!std::isfinite(value)) fail(" is not a number");
  if (joint.type == JointType::Continuous)  // as MoveIt's enforceBounds: the same angle
    return std::remainder(value, 2 * std::numbers::pi);
  if (value < joint.lower - kJointBoundsMargin || value > joint.upper + kJointBoundsMargin) {
    fail(" is outside its limits [" + std::to_string(joint.lower) + ", " +
         std::to_string(joint.upper) + "] by more than the bounds margin " +
         std::to_string(kJointBoundsMargin));
  }
  return std::clamp(value, joint.lower, joint.upper);
}

std::vector<double> actuatedConfiguration(const Robot& robot, const NamedPositions& positions,
                                          const std::string& what) {
  std::vector<double> q;
  for (const int j : robot.actuatedJoints()) {
    const Joint& joint = robot.joints()[static_cast<std::size_t>(j)];
    const auto it = std::find(positions.names.begin(), positions.names.end(), joint.name);
    if (it == positions.names.end())
      throw InvalidArgument(what + " has no position for joint '" + joint.name + "'");
    q.push_back(jointValueWithinLimits(
        joint, positions.positions[static_cast<std::size_t>(it - positions.names.begin())], what));
  }
  return q;
}

RequestRobot robotForRequest(Robot robot, const std::vector<SrdfGroup>& groups, const Scene& scene,
                             const PlanRequest& request, const std::string& source) {
  RequestRobot result{std::move(robot), {}};
  Robot& r = result.robot;
  const auto group = std::find_if(groups.begin(), groups.end(),
                                  [&](const SrdfGroup& g) { return g.name == request.group; });
  if (group != groups.end()) {
    if (group->joints.empty())
      throw InvalidArgument(source + ": group '" + request.group + "' moves no joint of robot '" +
                            r.name() + "'");
    r.setActuatedJoints(group->joints);
  } else if (!request.group.empty() && !groups.empty()) {
    result.warning = source + ": the SRDF has no group '" + request.group +
                     "': planning the robot's actuated joints";
  }
  const auto hold = [&](const NamedPositions& state, const std::string& what) {
    for (std::size_t i = 0; i < state.names.size(); ++i) {
      const auto joint = std::find_if(r.joints().begin(), r.joints().end(),
                                      [&](const Joint& j) { return j.name == state.names[i]; });
      if (joint == r.joints().end() || !joint->movable() || joint->mimic ||
          r.followsConfiguration(static_cast<int>(joint - r.joints().begin())))
        continue;
      r.setHeldPosition(joint->name, jointValueWithinLimits(*joint, state.positions[i], what));
    }
  };
  hold(scene.robotState, source + ": the scene's robot_state");
  hold(request.start, source + ": start_state");
  return result;
}

RequestEnds requestEnds(const Robot& robot, const PlanRequest& request, const std::string& source) {
  const auto asVector = [](const std::vector<double>& v) {
    return Eigen::VectorXd(
        Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
  };
  return {asVector(actuatedConfiguration(robot, request.start, source + ": start")),
          asVector(actuatedConfiguration(robot, request.goal, source + ": goal"))};
}

}  // namespace fastron
