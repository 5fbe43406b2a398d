// fastron robots: the shipped robots with their joints and limits.

#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/geometry/robot_library.h"

namespace fastron::cli {
namespace {

int runRobots(const std::string& only) {
  for (const RobotEntry& entry : shippedRobots()) {
    if (!only.empty() && entry.name != only) continue;
    const Robot robot = loadRobot(entry.name);
    std::cout << entry.name << ": " << entry.description << '\n';
    std::cout << "  urdf " << entry.urdf.string() << ", " << robot.links().size() << " links, "
              << robot.shapes().size() << " collision shapes\n";
    const JointLimits limits = robot.limits();
    std::cout << "  actuated joints (" << robot.dof() << "):\n";
    for (std::size_t j = 0; j < robot.dof(); ++j) {
      const auto& joint = robot.joints()[static_cast<std::size_t>(robot.actuatedJoints()[j])];
      std::cout << "    " << std::left << std::setw(22) << joint.name << std::setw(11)
                << (joint.type == JointType::Prismatic ? "prismatic" : "revolute") << "["
                << limits.lower()[static_cast<Eigen::Index>(j)] << ", "
                << limits.upper()[static_cast<Eigen::Index>(j)] << "]\n";
    }
    for (const auto& [joint, value] : entry.held)
      std::cout << "  held: " << joint << " = " << value << '\n';
    std::cout << '\n';
  }
  return 0;
}

}  // namespace

void addRobotsCommand(CLI::App& app, int& exitCode) {
  auto only = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("robots", "List the shipped robots with their joints and limits");
  cmd->add_option("name", *only, "show only this robot");
  cmd->callback([only, &exitCode] {
    if (!only->empty()) loadRobot(*only);  // a clear error for an unknown name
    exitCode = runRobots(*only);
  });
}

}  // namespace fastron::cli
