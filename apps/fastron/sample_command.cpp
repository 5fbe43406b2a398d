// fastron sample: uniform configurations of a robot in a scene, labelled by an exact checker (FCL
// unless told), as a dataset.

#include <algorithm>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/proxy/labelling.h"
#include "report_format.h"
#include "robot_options.h"
#include "scene_options.h"

namespace fastron::cli {
namespace {

struct SampleOptions {
  RobotOptions robot;
  SceneOptions scene;
  std::string output;
  std::size_t count = 10000;
  std::uint64_t seed = 1;
};

int runSample(const SampleOptions& o) {
  const Robot robot = loadRobotFromOptions(o.robot);
  const Scene scene = sceneFromOptions(o.scene);
  const auto oracle = checkerFromOptions(o.scene, robot, scene, "tables: ");
  Dataset data;
  Rng rng(o.seed);
  data.points = uniformConfigurations(robot.limits(), o.count, rng);
  data.labels = labelConfigurations(*oracle, data.points);
  data.columnNames = robot.actuatedJointNames();
  writeDataset(data, o.output);
  const auto colliding = std::count(data.labels.begin(), data.labels.end(), std::int8_t{1});
  std::cout << "wrote " << o.output << ": " << data.size() << " configurations of " << robot.name()
            << " (" << robot.dof() << " joints) in " << o.scene.file << ", "
            << rate(static_cast<double>(colliding) / static_cast<double>(data.size()))
            << " in collision under " << oracle->name() << "\n";
  return 0;
}

}  // namespace

void addSampleCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<SampleOptions>();
  CLI::App* cmd = app.add_subcommand(
      "sample", "Write labelled uniform configurations of a robot in a scene (CSV or .npy)");
  addRobotOptions(*cmd, o->robot);
  addSceneOptions(
      *cmd, o->scene,
      {.selfCollisionHelp = "label self-collisions as collisions too", .checkerRole = "labels"});
  cmd->add_option("-n,--count", o->count, "how many configurations")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("-o,--output", o->output, "dataset to write (.csv or .npy)")->required();
  cmd->add_option("--seed", o->seed, "seed of the samples")->capture_default_str();
  cmd->callback([o, &exitCode] { exitCode = runSample(*o); });
}

}  // namespace fastron::cli
