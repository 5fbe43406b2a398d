// fastron train: Algorithm 1 on a labelled dataset, written as a model file.

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <numeric>
#include <optional>
#include <span>
#include <sstream>

#include "commands.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model_file.h"
#include "fastron/core/trainer.h"

#include "fastron/pipeline/held_out_model.h"
#include "fastron/proxy/held_out_training.h"
#include "fastron/proxy/proxy_collision_detector.h"
#include "report_format.h"
#include "robot_options.h"
#include "scene_options.h"

namespace fastron::cli {
namespace {

struct TrainOptions {
  std::string data, output, kernel = "rq";
  std::vector<std::string> limits;
  RobotOptions robot;
  SceneOptions scene;
  FeatureOptions features;
  std::optional<double> gamma, beta;
  std::optional<std::uint32_t> kernelBlock;
  std::optional<double> wholeShare;
  std::optional<std::size_t> maxIterations, maxSupport;
  std::size_t samples = kSceneSamples, activeLearning = 0;
  HeldOutTargets heldOut;
  std::vector<double> margins{kGrownObstacleMargins.begin(), kGrownObstacleMargins.end()};
  double holdout = 0;
  std::uint64_t seed = 1;
  bool secondCandidate = true;
  bool featuresGiven = false;       ///< --features on the command line
  bool controlPointsGiven = false;  ///< any --control-* option on the command line
};

/// --robot with --self-collision and neither --scene nor --data: a model of the robot's
/// self-collisions alone, for `fastron plan --self-model`.
bool selfCollisionsAlone(const TrainOptions& o) {
  return o.data.empty() && o.scene.file.empty() && o.scene.selfCollision && !o.robot.robot.empty();
}

/// "lo:hi" per joint, or the dataset's bounding box when none are given.
JointLimits parseLimits(const std::vector<std::string>& items, const Dataset& data) {
  const auto d = static_cast<Eigen::Index>(data.dim());
  if (items.empty()) return rangeOf(data.points, "give --limits");
  if (static_cast<Eigen::Index>(items.size()) != d) {
    throw InvalidArgument("--limits has " + std::to_string(items.size()) +
                          " entries but the data has " + std::to_string(d) +
                          " configuration columns");
  }
  Eigen::VectorXd lower(d), upper(d);
  for (Eigen::Index j = 0; j < d; ++j) {
    const std::string& item = items[static_cast<std::size_t>(j)];
    const std::size_t colon = item.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument(item);
      lower[j] = std::stod(item.substr(0, colon));
      upper[j] = std::stod(item.substr(colon + 1));
    } catch (const std::logic_error&) {
      throw InvalidArgument("--limits entry '" + item + "' is not LOWER:UPPER");
    }
  }
  return {lower, upper};
}

/// `defaults` with what the options give instead.
TrainParams withOptions(TrainParams defaults, const TrainOptions& o) {
  defaults.kernel.type = parseKernelType(o.kernel);
  defaults.kernel.gamma = o.gamma.value_or(defaults.kernel.gamma);
  defaults.kernel.block = o.kernelBlock.value_or(defaults.kernel.block);
  defaults.kernel.wholeShare = o.wholeShare.value_or(defaults.kernel.wholeShare);
  defaults.beta = o.beta.value_or(defaults.beta);
  defaults.maxIterations = o.maxIterations.value_or(defaults.maxIterations);
  defaults.maxSupportPoints = o.maxSupport.value_or(defaults.maxSupportPoints);
  return defaults;
}

/// `params` with the cap of a robot's models (a robot's dataset).
TrainParams forRobot(TrainParams params) {
  params.maxSupportPoints = kRobotSupportCap;
  return params;
}

void printParams(const TrainParams& params, const FeatureMap& features) {
  std::cout << "features      " << features.summary() << '\n';
  if (features.kind() == FeatureKind::Kinematic) {
    std::cout << "control       ";
    const auto points = features.kinematics()->description().points;
    for (std::size_t p = 0; p < points.size(); ++p) {
      std::cout << (p ? ", " : "") << points[p].link;
      if (!points[p].offset.isZero()) {
        std::cout << " + (" << points[p].offset.transpose().format({3, 0, ", "}) << ")";
      }
    }
    std::cout << '\n';
  }
  std::cout << "kernel        " << toString(params.kernel.type) << ", gamma " << params.kernel.gamma
            << ", " << describeTerms(params.kernel, features.featureDim()) << ", beta "
            << params.beta << '\n';
}

void printReport(const UpdateReport& report) {
  std::cout << "update        " << report.iterations
            << " iterations, stopped: " << toString(report.stopReason)
            << (report.reverted ? " (reverted to the better earlier solution)" : "") << ", "
            << durationText(inSeconds(report.elapsed));
  if (report.sharedIterations > 0) {
    std::cout << " (" << report.sharedIterations << " iterations shared by two cores)";
  }
  std::cout << '\n';
  std::cout << "support set   " << report.supportCount << " points; " << report.misclassified
            << " training points misclassified\n";
}

void printRounds(const HeldOutTraining& trained, const std::vector<double>& margins,
                 std::span<const ModelCandidate> alternatives) {
  for (std::size_t r = 0; r < trained.rounds.size(); ++r) {
    const HeldOutRound& round = trained.rounds[r];
    std::cout << "held out      model of " << round.trainingSamples << " samples";
    if (round.candidate > 0) {
      const ModelCandidate& candidate = alternatives[round.candidate - 1];
      std::cout << " (second candidate: " << candidate.features.summary() << ", beta "
                << candidate.params.beta << ")";
    }
    if (round.grownLevel > 0) {
      std::cout << " (obstacles grown " << margins[round.grownLevel - 1] * 1000 << " mm)";
    }
    std::cout << ", |S| " << round.supportCount << ", on " << round.heldOut.total()
              << " fresh configurations: accuracy " << rate(round.heldOut.accuracy()) << ", TPR "
              << rate(round.heldOut.tpr()) << ", TNR " << rate(round.heldOut.tnr())
              << (r == trained.chosenRound ? " (kept)" : "") << '\n';
  }
}

/// fastron train --robot R --scene S: FCL-labelled uniform samples and Algorithm 1, then either
/// rounds on fresh held-out configurations until the targets are met, or K rounds of active
/// learning (Algorithm 2).
int trainOnScene(const TrainOptions& o) {
  if (o.activeLearning > 0 && o.heldOut.samplesPerRound > 0) {
    throw InvalidArgument(
        "--active-learning replaces the held-out rounds: give --held-out 0 with it");
  }
  const Robot robot = loadRobotFromOptions(o.robot);
  const bool selfAlone = selfCollisionsAlone(o);
  const Scene scene = sceneFromOptions(o.scene);
  // Self-collisions depend on the joint values alone, and a kernel over them modelled them better
  // than one over control points (docs/log/2026-11-25-a-self-collision-model-learned-once.md, "A
  // self-collision model learned once").
  FeatureOptions featureOptions = o.features;
  if (selfAlone && !o.featuresGiven) featureOptions.kind = "joints";
  // A scene's obstacles: point terms (sceneTrainParams), whose points must lie wherever a link can
  // touch (pipeline::heldOutControlPoints).
  if (!o.controlPointsGiven) {
    featureOptions.automatic = pipeline::heldOutControlPoints(o.scene.selfCollision);
  }
  const FeatureMap features = featuresFromOptions(featureOptions, robot);
  ProxyParams params;
  params.train = withOptions(sceneTrainParams(features.kind(), o.scene.selfCollision), o);
  params.seed = o.seed;
  params.relabelSupport = false;  // the scene stands still
  std::cout << "robot         " << robot.name() << ", " << robot.dof() << " actuated joints\n";
  if (selfAlone) {
    std::cout << "scene         none: a model of the robot's self-collisions alone\n";
  } else {
    std::cout << "scene         " << o.scene.file << ", " << scene.size() << " obstacle(s)\n";
  }
  printParams(params.train, features);
  std::shared_ptr<const Model> model;
  if (o.heldOut.samplesPerRound > 0) {
    pipeline::HeldOutModelOptions options;
    options.samples = o.samples;
    options.targets = o.heldOut;
    options.margins = o.margins;
    options.selfCollision = o.scene.selfCollision;
    options.padding = o.scene.padding;
    options.selfPairTables = checkerOptionsFor(o.scene, robot, "tables        ").selfPairTables;
    options.checker = o.scene.checker;
    // The other candidates were measured with automatic task-space control points.
    if (o.secondCandidate && o.features.controlLinks.empty())
      options.automatic = featureOptions.automatic;
    options.candidateBeta = o.beta;
    options.seed = o.seed;
    const pipeline::HeldOutModel made =
        pipeline::trainHeldOutModel(robot, scene, features, params.train, options);
    const HeldOutTraining& trained = made.training;
    std::cout << "samples       " << o.samples << " labelled by " << made.oracle
              << ", then rounds of " << o.heldOut.samplesPerRound << " held out (targets: accuracy "
              << o.heldOut.accuracy << ", TPR " << o.heldOut.truePositiveRate << ")\n";
    printRounds(trained, made.margins, made.candidates);
    if (trained.rounds[trained.chosenRound].candidate > 0) {
      const ModelCandidate& kept =
          made.candidates[trained.rounds[trained.chosenRound].candidate - 1];
      std::cout << "kept          the second candidate:\n";
      printParams(kept.params, kept.features);
    }
    printReport(trained.update);
    std::cout << "time          " << durationText(made.seconds) << " for labelling and training\n";
    model = trained.model;
  } else {
    const std::shared_ptr<const SceneChecker> oracle =
        checkerFromOptions(o.scene, robot, scene, "tables        ");
    ProxyCollisionDetector proxy(oracle, features, params);
    StepReport step = proxy.initialize(o.samples);
    std::cout << "samples       " << o.samples << " labelled by " << oracle->name() << " in "
              << durationText(inSeconds(step.labelTime)) << '\n';
    printReport(step.update);
    for (std::size_t k = 0; k < o.activeLearning; ++k) {
      step = proxy.step();
      std::cout << "active        round " << (k + 1) << ": " << step.added << " new points, |S| "
                << step.update.supportCount << ", " << durationText(inSeconds(step.total)) << '\n';
    }
    model = proxy.model();
  }
  saveModel(*model, o.output);
  std::cout << "model         " << o.output << '\n';
  return 0;
}

int runTrain(const TrainOptions& o) {
  if (o.holdout < 0 || o.holdout >= 1) throw InvalidArgument("--holdout must be in [0, 1)");
  if (!selfCollisionsAlone(o) && o.data.empty() == o.scene.file.empty()) {
    throw InvalidArgument(
        "give --data (a labelled dataset) or --robot with --scene, not both (or --robot with "
        "--self-collision alone: a model of the robot's self-collisions)");
  }
  if (o.data.empty()) {  // a scene, or the robot's self-collisions alone
    if (o.robot.robot.empty()) throw InvalidArgument("--scene needs --robot");
    if (!o.limits.empty())
      throw InvalidArgument("--limits goes with --data; the robot has its own");
    return trainOnScene(o);
  }
  const Dataset data = readDataset(o.data);
  std::optional<Robot> robot;
  if (!o.robot.robot.empty()) {
    if (!o.limits.empty())
      throw InvalidArgument("--limits goes with --data alone; the robot has its own");
    robot = loadRobotFromOptions(o.robot);
    if (robot->dof() != data.dim()) {
      throw InvalidArgument(o.data + " has " + std::to_string(data.dim()) +
                            " configuration columns but " + robot->name() + " has " +
                            std::to_string(robot->dof()) + " actuated joints");
    }
  }
  const FeatureMap features = robot ? featuresFromOptions(o.features, *robot)
                                    : FeatureMap::jointScaling(parseLimits(o.limits, data));
  // A dataset without a robot keeps the settings of old (gamma 10, beta 1, cap 3000).
  const TrainParams params =
      withOptions(robot ? forRobot(defaultTrainParams(features.kind())) : TrainParams{}, o);

  const auto [train, test] = splitHoldout(data, o.holdout, o.seed);

  Trainer trainer(features, params);
  trainer.addPoints(train.points, train.labels);
  const UpdateReport report = trainer.update(0);  // on two cores when the data are large enough
  const auto model = trainer.model();
  saveModel(*model, o.output);

  std::cout << "data          " << o.data << ": " << data.size() << " configurations, dimension "
            << data.dim() << " (" << train.size() << " for training, " << test.size()
            << " held out)\n";
  const JointLimits& limits = features.limits();
  std::cout << "joint limits  "
            << (robot              ? "the robot's:"
                : o.limits.empty() ? "from the data's range:"
                                   : "given:");
  for (std::size_t j = 0; j < data.dim(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    std::cout << ' ' << limits.lower()[jj] << ':' << limits.upper()[jj];
  }
  std::cout << '\n';
  printParams(params, features);
  printReport(report);
  if (test.size() > 0) {
    const ConfusionCounts c = evaluate(*model, test.points, test.labels);
    std::cout << "held out      accuracy " << rate(c.accuracy()) << ", TPR " << rate(c.tpr())
              << ", TNR " << rate(c.tnr()) << '\n';
  }
  std::cout << "model         " << o.output << '\n';
  return 0;
}

/// With --scene: the samples, the held-out rounds and their targets, the margins, the candidates.
void addSceneTrainingOptions(CLI::App& cmd, TrainOptions& o) {
  cmd.add_option("--samples", o.samples,
                 "with --scene: uniform samples labelled by the exact checker")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd.add_option("--active-learning", o.activeLearning,
                 "with --scene: rounds of active learning (Algorithm 2) after the first update")
      ->capture_default_str();
  cmd.add_option("--held-out", o.heldOut.samplesPerRound,
                 "with --scene: fresh labelled configurations per round on which the model "
                 "is measured; below the targets it learns them and is measured on new ones "
                 "(0: no rounds). With fk features and no --self-collision the kernel has point "
                 "terms alone on up to 10 automatic control points along the links' geometry "
                 "(unless a --control-* option is given), answered by a point field")
      ->capture_default_str();
  cmd.add_option("--target-accuracy", o.heldOut.accuracy,
                 "with --scene: held-out accuracy to reach")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd.add_option("--target-tpr", o.heldOut.truePositiveRate, "with --scene: held-out TPR to reach")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd.add_option("--max-samples", o.heldOut.maxTrainingSamples,
                 "with --scene: no more held-out rounds once the model has learned this many "
                 "labelled configurations")
      ->capture_default_str();
  cmd.add_option("--margins", o.margins,
                 "with --scene: obstacle margins (m, increasing, comma-separated) of the labels "
                 "a round learns when it meets the target accuracy and misses the TPR; the "
                 "rounds are measured on exact labels (--margins 0: none)")
      ->delimiter(',')
      ->check(numberAbove(0, true))
      ->capture_default_str();
  cmd.add_flag("--second-candidate,!--no-second-candidate", o.secondCandidate,
               "with --scene and automatic fk control points, no --self-collision: a round that "
               "misses the targets also trains a model with one more control point and beta 10 "
               "(or --beta) "
               "on the same samples, and the one closer to the targets is kept (default: on)");
}

/// Algorithm 1's settings: kernel, its terms, conditional bias, limits of the run.
void addAlgorithmOptions(CLI::App& cmd, TrainOptions& o) {
  cmd.add_option("--gamma", o.gamma,
                 "kernel width (default: 10 for a dataset alone; with --robot 40 for fk "
                 "features, 60 for fk with --scene, 5 for joints)");
  cmd.add_option("--kernel", o.kernel, "rq (rational quadratic) or gaussian")
      ->capture_default_str();
  cmd.add_option("--kernel-block", o.kernelBlock,
                 "features per kernel point term: 0 one term over all features, 3 one term per "
                 "control point (default: 3 for fk features without --self-collision, 0 "
                 "otherwise)");
  cmd.add_option("--kernel-whole-share", o.wholeShare,
                 "with point terms: the whole feature vector's share of the kernel, in [0, 1] "
                 "(default 0.5)")
      ->check(CLI::Range(0.0, 1.0));
  cmd.add_option("--beta", o.beta,
                 "conditional bias, >= 1 (default: 1 for a dataset alone; with --robot 30 for "
                 "fk features, 40 for fk with --scene, 10 for fk with --self-collision, 500 for "
                 "joints)");
  cmd.add_option("--max-iter", o.maxIterations,
                 "iteration limit (default 5000; 20000 with --scene)");
  cmd.add_option("--max-support", o.maxSupport,
                 "support-point cap (default 3000; 5000 with --robot)");
}

}  // namespace

void addTrainCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<TrainOptions>();
  CLI::App* cmd = app.add_subcommand(
      "train",
      "Train a Fastron model (Algorithm 1) on a labelled dataset, or on a robot in a scene");
  cmd->add_option("--data", o->data, "CSV or .npy: configuration columns, then the label +1 / -1")
      ->check(CLI::ExistingFile);
  addRobotOptions(*cmd, o->robot, false);
  addSceneOptions(
      *cmd, o->scene,
      {.sceneRequired = false,
       .selfCollisionHelp = "with --scene: label self-collisions as collisions too; with --robot "
                            "alone: learn the robot's self-collisions alone (joint features by "
                            "default), for fastron plan --self-model",
       .checkerRole = "labels the samples (with --robot)"});
  addFeatureOptions(*cmd, o->features);
  addSceneTrainingOptions(*cmd, *o);
  cmd->add_option("-o,--output", o->output, "model file to write")->required();
  addAlgorithmOptions(*cmd, *o);
  cmd->add_option(
         "--limits", o->limits,
         "joint limits LOWER:UPPER per column, comma-separated (write --limits=-3.14:3.14,...); "
         "default: the data's range")
      ->delimiter(',');
  cmd->add_option("--holdout", o->holdout, "share of the data held out for validation")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of the held-out split and of sampling")
      ->capture_default_str();
  cmd->callback([o, cmd, &exitCode] {
    o->featuresGiven = cmd->count("--features") > 0;
    o->controlPointsGiven = false;
    for (const char* name : {"--control-points", "--control-spacing", "--control-per-body",
                             "--control-rule", "--control-geometry"}) {
      o->controlPointsGiven = o->controlPointsGiven || cmd->count(name) > 0;
    }
    exitCode = runTrain(*o);
  });
}

}  // namespace fastron::cli
