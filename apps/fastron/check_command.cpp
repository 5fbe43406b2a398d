// fastron check: is this configuration in collision? Every exact checker answers; exit 0 when the
// one of --checker (FCL unless told) finds it free, 1 when in collision, 2 on an error.

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/error.h"
#include "fastron/geometry/robot_library.h"
#include "robot_options.h"
#include "scene_options.h"

namespace fastron::cli {
namespace {

struct CheckOptions {
  RobotOptions robot;
  SceneOptions scene;
  std::vector<double> config;
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
  const Scene scene = sceneFromOptions(o.scene);
  std::cout << "robot   " << robot.name() << ", " << robot.dof() << " actuated joints"
            << (o.scene.selfCollision ? ", self-collision on" : "")
            << (o.scene.padding > 0 ? ", padded" : "") << '\n';
  std::cout << "scene   " << o.scene.file << ", " << scene.size()
            << (scene.size() == 1 ? " obstacle\n" : " obstacles\n");
  bool collides = false;
  for (const SceneCheckerKind& kind : sceneCheckerKinds()) {
    std::shared_ptr<SceneChecker> checker;
    try {
      checker = makeSceneChecker(kind.name, robot, scene, checkerOptionsFrom(o.scene));
    } catch (const Unsupported& e) {
      // A backend that cannot check this scene (GJK and a point cloud) says so; the one that
      // decides the exit code must answer.
      if (kind.name == o.scene.checker) throw;
      std::string name = kind.name;
      std::transform(name.begin(), name.end(), name.begin(), ::toupper);
      std::cout << std::left << std::setw(8) << name << "cannot check: " << e.what() << '\n';
      continue;
    }
    const auto contact = checker->firstContact(o.config);
    std::cout << std::left << std::setw(8) << checker->name();
    if (contact) {
      std::cout << "in collision: " << describe(*contact) << '\n';
    } else if (checker->measuresDistance()) {
      std::cout << "free, " << std::fixed << std::setprecision(4) << checker->distance(o.config)
                << " m from the nearest obstacle\n";
    } else {
      std::cout << "free\n";
    }
    if (kind.name == o.scene.checker) collides = contact.has_value();
  }
  return collides ? 1 : 0;
}

}  // namespace

void addCheckCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<CheckOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Check one configuration with every exact checker (exit 0: free under --checker, 1: in "
      "collision, 2: error)");
  addRobotOptions(*cmd, o->robot);
  addSceneOptions(*cmd, o->scene,
                  {.checkerRole = "decides the exit code", .selfPairTables = false});
  cmd->add_option("--config", o->config, "joint values of the actuated joints, comma-separated")
      ->required()
      ->delimiter(',')
      ->allow_extra_args(false);
  cmd->callback([o, &exitCode] { exitCode = runCheck(*o); });
}

}  // namespace fastron::cli
