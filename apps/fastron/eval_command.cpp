// fastron eval: a model against a labelled dataset, or against FCL on fresh samples of a scene.

#include <iostream>
#include <memory>
#include <optional>

#include "commands.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model_file.h"
#include "fastron/core/simd.h"
#include "fastron/experiments/common.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/proxy/labelling.h"
#include "report_format.h"
#include "robot_options.h"

namespace fastron::cli {
namespace {

struct EvalOptions {
  std::string model, data, scene;
  RobotOptions robot;
  std::size_t samples = 20000;
  std::uint64_t seed = 2;
  bool selfCollision = false;
};

constexpr double kTimingSeconds = 0.2;  // each timing repeats the configurations this long

int runEval(const EvalOptions& o) {
  if (o.data.empty() == o.scene.empty()) {
    throw InvalidArgument("give --data (a labelled dataset) or --robot with --scene, not both");
  }
  if (!o.scene.empty() && o.robot.robot.empty()) throw InvalidArgument("--scene needs --robot");
  std::optional<Robot> robot;
  if (!o.robot.robot.empty()) robot = loadRobotFromOptions(o.robot);
  const Model model = robot ? loadModelFor(o.model, *robot) : loadModel(o.model);

  Dataset data;
  std::shared_ptr<const FclChecker> fcl;
  if (!o.scene.empty()) {
    fcl = std::make_shared<const FclChecker>(*robot, loadScene(o.scene),
                                             CheckerOptions{o.selfCollision});
    Rng rng(o.seed);
    data.points = uniformConfigurations(robot->limits(), o.samples, rng);
    data.labels = labelConfigurations(*fcl, data.points);
  } else {
    data = readDataset(o.data);
  }
  if (model.dim() != data.dim()) {
    throw InvalidArgument(o.data + " has " + std::to_string(data.dim()) +
                          " configuration columns, but the model " + o.model + " has dimension " +
                          std::to_string(model.dim()));
  }
  const ConfusionCounts c = evaluate(model, data.points, data.labels);

  const double query = experiments::meanSecondsPerCall(
      data.points, [&](const double* q) { return model.inCollision(q); }, kTimingSeconds);
  std::vector<float> x(model.featureDim());
  const double features = experiments::meanSecondsPerCall(
      data.points,
      [&](const double* q) {
        model.features().map(q, x.data());
        return x[0] > 0;
      },
      kTimingSeconds);

  std::cout << "model       " << o.model << ": dimension " << model.dim() << ", "
            << model.supportCount() << " support points, features " << model.features().summary()
            << ", kernel " << toString(model.kernel().type) << " gamma " << model.kernel().gamma
            << ", " << describeTerms(model.kernel(), model.featureDim()) << '\n';
  if (fcl) {
    std::cout << "data        " << data.size() << " uniform configurations of " << o.scene
              << " labelled by FCL (seed " << o.seed << "), "
              << rate(static_cast<double>(c.truePositives + c.falseNegatives) /
                      static_cast<double>(data.size()))
              << " in collision\n";
  } else {
    std::cout << "data        " << o.data << ": " << data.size() << " configurations\n";
  }
  std::cout << "accuracy    " << rate(c.accuracy()) << "\nTPR         " << rate(c.tpr())
            << "\nTNR         " << rate(c.tnr()) << '\n';
  std::cout << "confusion   TP " << c.truePositives << ", TN " << c.trueNegatives << ", FP "
            << c.falsePositives << ", FN " << c.falseNegatives << '\n';
  std::cout << "query time  " << durationText(query) << " per configuration (features "
            << durationText(features) << ", kernel sum "
            << durationText(std::max(0.0, query - features)) << ", " << toString(activeSimdPath())
            << ")\n";
  if (fcl) {
    const double exact = experiments::meanSecondsPerCheck(data.points, *fcl, kTimingSeconds);
    std::cout << "FK+FCL      " << durationText(exact) << " per configuration: the model is "
              << times(exact / query) << " faster\n";
  }
  return 0;
}

}  // namespace

void addEvalCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval", "Evaluate a model on a labelled dataset, or against FCL on a robot in a scene");
  cmd->add_option("--model", o->model, "model file from fastron train")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--data", o->data, "CSV or .npy labelled dataset")->check(CLI::ExistingFile);
  addRobotOptions(*cmd, o->robot, false);
  cmd->add_option("--scene", o->scene,
                  "with --robot: compare with FCL on fresh uniform samples of this scene")
      ->check(CLI::ExistingFile);
  cmd->add_option("--samples", o->samples, "with --scene: how many samples")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--seed", o->seed, "with --scene: seed of the samples")->capture_default_str();
  cmd->add_flag("--self-collision", o->selfCollision,
                "with --scene: count self-collisions as collisions");
  cmd->callback([o, &exitCode] { exitCode = runEval(*o); });
}

}  // namespace fastron::cli
