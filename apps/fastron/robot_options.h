#pragma once
// The options that choose a robot: --robot, --joints, --package-path.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "fastron/geometry/robot.h"

namespace fastron::cli {

struct RobotOptions {
  std::string robot;
  std::vector<std::string> joints;
  std::vector<std::string> packagePaths;
};

void addRobotOptions(CLI::App& cmd, RobotOptions& options);

/// The shipped robot or URDF, with --joints applied.
Robot loadRobotFromOptions(const RobotOptions& options);

/// The joint values given to `option` (e.g. "--config") as a configuration of `robot`; throws
/// InvalidArgument naming the option, the count and the robot's actuated joints when the count
/// differs.
Eigen::VectorXd configurationFromOption(const std::vector<double>& values, const Robot& robot,
                                        const char* option);

}  // namespace fastron::cli
