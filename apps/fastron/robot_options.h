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

}  // namespace fastron::cli
