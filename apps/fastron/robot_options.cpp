#include "robot_options.h"

#include "fastron/core/error.h"
#include "fastron/geometry/robot_library.h"

namespace fastron::cli {

void addRobotOptions(CLI::App& cmd, RobotOptions& options) {
  cmd.add_option("--robot", options.robot, "a shipped robot (see fastron robots) or a URDF file")
      ->required();
  cmd.add_option(
         "--joints", options.joints,
         "actuated joints, comma-separated (default: the robot's own list); others stay at 0")
      ->delimiter(',');
  cmd.add_option("--package-path", options.packagePaths,
                 "folder searched for package:// and relative mesh paths (repeatable)");
}

Robot loadRobotFromOptions(const RobotOptions& options) {
  UrdfOptions urdf;
  for (const auto& p : options.packagePaths) urdf.searchPaths.emplace_back(p);
  Robot robot = loadRobot(options.robot, urdf);
  if (!options.joints.empty()) robot.setActuatedJoints(options.joints);
  return robot;
}

Eigen::VectorXd configurationFromOption(const std::vector<double>& values, const Robot& robot,
                                        const char* option) {
  if (values.size() != robot.dof()) {
    std::string names;
    for (const auto& n : robot.actuatedJointNames()) names += (names.empty() ? "" : ", ") + n;
    throw InvalidArgument(std::string(option) + " has " + std::to_string(values.size()) +
                          " values but " + robot.name() + " has " + std::to_string(robot.dof()) +
                          " actuated joints (" + names + ")");
  }
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace fastron::cli
