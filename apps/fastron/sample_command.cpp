// fastron sample: uniform configurations of a robot in a scene, labelled by FCL, as a dataset.

#include <algorithm>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/proxy/labelling.h"
#include "report_format.h"
#include "robot_options.h"

namespace fastron::cli {
namespace {

struct SampleOptions {
  RobotOptions robot;
  std::string scene, output;
  std::size_t count = 10000;
  std::uint64_t seed = 1;
  bool selfCollision = false;
};

int runSample(const SampleOptions& o) {
  const Robot robot = loadRobotFromOptions(o.robot);
  const Scene scene = loadScene(o.scene);
  const FclChecker fcl(robot, scene, CheckerOptions{o.selfCollision});
  Dataset data;
  Rng rng(o.seed);
  data.points = uniformConfigurations(robot.limits(), o.count, rng);
  data.labels = labelConfigurations(fcl, data.points);
  data.columnNames = robot.actuatedJointNames();
  writeDataset(data, o.output);
  const auto colliding = std::count(data.labels.begin(), data.labels.end(), std::int8_t{1});
  std::cout << "wrote " << o.output << ": " << data.size() << " configurations of " << robot.name()
            << " (" << robot.dof() << " joints) in " << o.scene << ", "
            << rate(static_cast<double>(colliding) / static_cast<double>(data.size()))
            << " in collision under FCL\n";
  return 0;
}

}  // namespace

void addSampleCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<SampleOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sample", "Write FCL-labelled uniform configurations of a robot in a scene (CSV or .npy)");
  addRobotOptions(*cmd, o->robot);
  cmd->add_option("--scene", o->scene, "the project's scene YAML or a MoveIt PlanningScene")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-n,--count", o->count, "how many configurations")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("-o,--output", o->output, "dataset to write (.csv or .npy)")->required();
  cmd->add_option("--seed", o->seed, "seed of the samples")->capture_default_str();
  cmd->add_flag("--self-collision", o->selfCollision, "label self-collisions as collisions too");
  cmd->callback([o, &exitCode] { exitCode = runSample(*o); });
}

}  // namespace fastron::cli
