// fastron check: is this configuration in collision? Exit 0 when FCL finds it free, 1 when in
// collision, 2 on an error.

#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "robot_options.h"

namespace fastron::cli {
namespace {

struct CheckOptions {
  RobotOptions robot;
  std::string scene;
  std::vector<double> config;
  bool selfCollision = false;
  double padding = 0;
};

int runCheck(const CheckOptions& o) {
  const Robot robot = loadRobotFromOptions(o.robot);
  configurationFromOption(o.config, robot, "--config");
  const JointLimits limits = robot.limits();
  for (std::size_t j = 0; j < robot.dof(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    if (!std::isfinite(o.config[j]))
      throw InvalidArgument("--config value " + std::to_string(j + 1) + " is not finite");
    if (o.config[j] < limits.lower()[jj] || o.config[j] > limits.upper()[jj]) {
      std::cerr << "fastron: warning: " << robot.actuatedJointNames()[j] << " = " << o.config[j]
                << " is outside its limits [" << limits.lower()[jj] << ", " << limits.upper()[jj]
                << "]\n";
    }
  }
  const Scene scene = loadScene(o.scene);
  const CheckerOptions options{o.selfCollision, o.padding};
  const FclChecker fcl(robot, scene, options);
  const GjkChecker gjk(robot, scene, options);

  std::cout << "robot   " << robot.name() << ", " << robot.dof() << " actuated joints"
            << (o.selfCollision ? ", self-collision on" : "") << (o.padding > 0 ? ", padded" : "")
            << '\n';
  std::cout << "scene   " << o.scene << ", " << scene.size()
            << (scene.size() == 1 ? " obstacle\n" : " obstacles\n");
  const auto contact = fcl.firstContact(o.config);
  std::cout << "FCL     ";
  if (contact) {
    std::cout << "in collision: " << describe(*contact) << '\n';
  } else {
    std::cout << "free, " << std::fixed << std::setprecision(4) << fcl.distance(o.config)
              << " m from the nearest obstacle\n";
  }
  std::cout << "GJK     " << (gjk.inCollision(o.config) ? "in collision" : "free") << '\n';
  return contact ? 1 : 0;
}

}  // namespace

void addCheckCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Check one configuration with FCL and GJK (exit 0: free, 1: in collision, 2: error)");
  addRobotOptions(*cmd, o->robot);
  cmd->add_option("--scene", o->scene, "scene file: the project's YAML or a MoveIt PlanningScene")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--config", o->config, "joint values of the actuated joints, comma-separated")
      ->required()
      ->delimiter(',')
      ->allow_extra_args(false);
  cmd->add_flag("--self-collision", o->selfCollision, "also check the robot against itself");
  cmd->add_option("--padding", o->padding, "grow the robot's shapes by this much (m)");
  cmd->callback([o, &exitCode] { exitCode = runCheck(*o); });
}

}  // namespace fastron::cli
