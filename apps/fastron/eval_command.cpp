// fastron eval: a model against a labelled dataset, or against an exact checker (FCL unless told)
// on fresh samples of a scene.

#include <algorithm>
#include <array>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "commands.h"
#include "fastron/baselines/original_fastron_query.h"
#include "fastron/core/active_learning.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model_file.h"
#include "fastron/core/simd.h"
#include "fastron/experiments/statistics.h"
#include "fastron/experiments/table.h"
#include "fastron/experiments/timing.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/planning/motion.h"
#include "fastron/proxy/labelling.h"
#include "plotting.h"
#include "report_format.h"
#include "robot_options.h"
#include "scene_options.h"

namespace fastron::cli {
namespace {

struct EvalOptions {
  std::string model, data, path, out;
  /// A joint-space model (the original Fastron's kind) timed with the original's query on the
  /// same configurations, beside this model's fastest answers.
  std::string original;
  RobotOptions robot;
  SceneOptions scene;
  std::size_t samples = 20000;
  std::uint64_t seed = 2;
  std::optional<double> resolution;  ///< with --path; default kPathResolution
  bool clearance = false, plot = true;
  /// Point terms only: also the answers of the model's point field (point_field.h).
  bool pointField = true;
  PointFieldOptions field;
};

constexpr double kPathResolution = 0.03;  // fastron plan's default edge resolution
constexpr double kTimingSeconds = 0.2;    // each timing repeats the configurations this long
constexpr std::size_t kMissLinksShown = 5;

/// "panda_link5 60, panda_hand 19, ...": the robot links of the collisions the model called free,
/// by the first contact the exact checker reports (the link, or "self" for a self-collision), most
/// first. Which links the model misses is what tells a user where a control point is lacking.
std::string missesByLink(const Model& model, const SceneChecker& exact, const Dataset& data) {
  std::map<std::string, std::size_t> counts;
  for (Eigen::Index i = 0; i < data.points.rows(); ++i) {
    if (data.labels[static_cast<std::size_t>(i)] <= 0) continue;
    const Eigen::VectorXd q = data.points.row(i).transpose();
    if (model.inCollision(q.data())) continue;
    const auto contact = exact.firstContact({q.data(), static_cast<std::size_t>(q.size())});
    if (!contact) continue;  // cannot happen: the checker labelled it colliding
    ++counts[contact->selfCollision ? contact->robotLink + " (self)" : contact->robotLink];
  }
  std::vector<std::pair<std::string, std::size_t>> sorted(counts.begin(), counts.end());
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  if (sorted.empty()) return "none";
  std::string text;
  for (std::size_t k = 0; k < sorted.size() && k < kMissLinksShown; ++k) {
    if (k > 0) text += ", ";
    text += sorted[k].first + " " + std::to_string(sorted[k].second);
  }
  if (sorted.size() > kMissLinksShown) {
    std::size_t rest = 0;
    for (std::size_t k = kMissLinksShown; k < sorted.size(); ++k) rest += sorted[k].second;
    text += ", other links " + std::to_string(rest);
  }
  return text;
}

/// Where the model is wrong about free states, by their distance to the nearest obstacle: for
/// each band, how many free states lie in it and the share the model calls colliding. A model
/// that is accurate on average can still close a passage that a planner needs, because the
/// states there lie close to obstacles (docs/log/2026-11-26-generated-cage-and-box-families.md,
/// "Families beyond the samples").
std::string freeStatesByClearance(const Dataset& data, const std::vector<double>& clearance,
                                  const Eigen::VectorXd& scores) {
  constexpr std::array<double, 3> kBounds{0.01, 0.02, 0.05};  // metres
  constexpr std::array<const char*, 4> kNames{"under 1 cm", "1-2 cm", "2-5 cm", "5 cm or more"};
  std::array<std::size_t, 4> free{}, wrong{};
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (data.labels[i] > 0) continue;
    const auto band = static_cast<std::size_t>(
        std::upper_bound(kBounds.begin(), kBounds.end(), clearance[i]) - kBounds.begin());
    ++free[band];
    if (scores[static_cast<Eigen::Index>(i)] > 0) ++wrong[band];
  }
  std::string text;
  for (std::size_t band = 0; band < free.size(); ++band) {
    if (band > 0) text += ", ";
    text += std::string(kNames[band]) + " " + std::to_string(free[band]);
    if (free[band] > 0) {
      text += " (" + rate(static_cast<double>(wrong[band]) / static_cast<double>(free[band])) +
              " called colliding)";
    }
  }
  return text;
}

/// The states along a path, one row each: where on the path (state index, joint-space distance
/// from the start), the joint values, FCL's answer, the model's score and answer, the clearance.
experiments::Table alongPathTable(const Dataset& data, const std::vector<std::string>& jointNames,
                                  const Eigen::VectorXd& scores,
                                  const std::vector<double>& clearance) {
  experiments::Table table;
  table.columns = {"state", "arc_length"};
  table.columns.insert(table.columns.end(), jointNames.begin(), jointNames.end());
  table.columns.insert(table.columns.end(),
                       {"fcl_collides", "score", "model_collides", "clearance_m"});
  const auto number = [](double value) {
    std::ostringstream text;
    text << std::setprecision(17) << value;
    return text.str();
  };
  double arc = 0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    if (i > 0) arc += (data.points.row(row) - data.points.row(row - 1)).norm();
    const Eigen::VectorXd q = data.points.row(row).transpose();
    std::vector<std::string> cells{std::to_string(i), number(arc)};
    for (Eigen::Index j = 0; j < q.size(); ++j) cells.push_back(number(q[j]));
    const double score = scores[row];
    cells.insert(cells.end(), {data.labels[i] > 0 ? "1" : "0", number(score), score > 0 ? "1" : "0",
                               number(clearance[i])});
    table.add(std::move(cells));
  }
  return table;
}

/// OUT/along_path.csv and, unless --no-plot, OUT/along_path.png (scripts/plot_along_path.py).
void writeAlongPath(const EvalOptions& o, const experiments::Table& table) {
  const std::filesystem::path dir(o.out);
  std::filesystem::create_directories(dir);
  table.writeCsv(dir / "along_path.csv");
  std::cout << "written     " << (dir / "along_path.csv").string();
  if (o.plot) {
    const std::string error = runPlotScript("plot_along_path.py", {dir.string()});
    if (error.empty()) {
      std::cout << ", " << (dir / "along_path.png").string();
    } else {
      std::cerr << "fastron: warning: no plot drawn: " << error << '\n';
    }
  }
  std::cout << '\n';
}

/// --robot with --self-collision alone: a model of the robot's self-collisions (fastron train
/// --robot R --self-collision), against the exact checker on the robot without obstacles.
bool selfCollisionsAlone(const EvalOptions& o) {
  return o.data.empty() && o.scene.file.empty() && o.scene.selfCollision && !o.robot.robot.empty();
}

/// Throws InvalidArgument naming the options that do not go together.
void checkEvalOptions(const EvalOptions& o) {
  const bool hasScene = !o.scene.file.empty();
  if (!selfCollisionsAlone(o) && o.data.empty() == !hasScene) {
    throw InvalidArgument(
        "give --data (a labelled dataset) or --robot with --scene, not both (or --robot with "
        "--self-collision alone: the robot's self-collisions)");
  }
  if (hasScene && o.robot.robot.empty()) throw InvalidArgument("--scene needs --robot");
  if (!o.out.empty() && o.path.empty()) throw InvalidArgument("--out needs --path");
  if (o.resolution && o.path.empty()) throw InvalidArgument("--resolution needs --path");
  if (!o.scene.allow.empty() && !hasScene) throw InvalidArgument("--allow needs --scene");
  if ((!o.path.empty() || o.clearance) && !hasScene) {
    throw InvalidArgument(std::string(o.path.empty() ? "--clearance" : "--path") +
                          " needs --robot and --scene");
  }
}

/// Configurations labelled by `exact`: uniform samples, or the states along --path.
Dataset labelledSamples(const EvalOptions& o, const Robot& robot, const SceneChecker& exact) {
  if ((o.clearance || !o.path.empty()) && !exact.measuresDistance()) {
    throw InvalidArgument(std::string(o.path.empty() ? "--clearance" : "--path") +
                          " needs a checker that measures distances, not " + exact.name());
  }
  Dataset data;
  if (o.path.empty()) {
    Rng rng(o.seed);
    data.points = uniformConfigurations(robot.limits(), o.samples, rng);
  } else {
    data.points = statesAlongPath(readPathCsv(o.path, robot.actuatedJointNames()),
                                  o.resolution.value_or(kPathResolution));
  }
  data.labels = labelConfigurations(exact, data.points);
  return data;
}

/// "data        20000 uniform configurations of S labelled by FCL (seed 2), 31.2% in collision".
void printDataLine(const EvalOptions& o, const Dataset& data, const ConfusionCounts& c,
                   const SceneChecker* exact) {
  if (!exact) {
    std::cout << "data        " << o.data << ": " << data.size() << " configurations\n";
    return;
  }
  std::cout << "data        " << data.size();
  if (o.path.empty()) {
    std::cout << " uniform configurations of "
              << (selfCollisionsAlone(o) ? std::string("the robot without obstacles")
                                         : o.scene.file)
              << " labelled by " << exact->name() << " (seed " << o.seed << "), ";
  } else {
    std::cout << " states along " << o.path << " (every " << o.resolution.value_or(kPathResolution)
              << " rad, as a planner checks its edges) in " << o.scene.file << " labelled by "
              << exact->name() << ", ";
  }
  std::cout << rate(static_cast<double>(c.truePositives + c.falseNegatives) /
                    static_cast<double>(data.size()))
            << " in collision\n";
}

/// The query times of a model's point field: its exact answers and its estimate alone.
struct FieldTimes {
  double exact = 0, estimate = 0;
};

/// For a model of point terms only: its point field, how many of the samples the grids answered
/// (alone, and with their fine blocks), that every answer equals the full sum's, and the field's
/// query time; then the same grids answering by their estimate alone (FieldAnswers::Estimate):
/// how many answers differ from the full sum's, its accuracy and TPR against the labels beside
/// the full sum's `full`, and its time.
FieldTimes printPointField(const EvalOptions& o, const Model& model, const Dataset& data,
                           const ConfusionCounts& full) {
  const auto start = std::chrono::steady_clock::now();
  const auto tabulated = model.withPointField(o.field);
  const double build =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  PointFieldOptions estimateOptions = o.field;
  estimateOptions.answers = FieldAnswers::Estimate;
  const auto estimated = model.withPointField(estimateOptions);
  const PointField& field = *tabulated->pointField();
  std::size_t decided = 0, fine = 0, equal = 0, estimateEqual = 0;
  std::vector<float> x(model.featureDim());
  for (Eigen::Index i = 0; i < data.points.rows(); ++i) {
    const double* q = data.points.row(i).data();
    model.features().map(q, x.data());
    decided += field.sign(x.data()) != 0;
    fine += field.signWithFineBlocks(x.data()) != 0;
    const bool collides = model.score(q) > 0;
    equal += tabulated->inCollision(q) == collides;
    estimateEqual += estimated->inCollision(q) == collides;
  }
  FieldTimes times;
  times.exact = experiments::meanSecondsPerCall(
      data.points, [&](const double* q) { return tabulated->inCollision(q); }, kTimingSeconds);
  times.estimate = experiments::meanSecondsPerCall(
      data.points, [&](const double* q) { return estimated->inCollision(q); }, kTimingSeconds);
  const ConfusionCounts c = evaluate(*estimated, data.points, data.labels);
  const auto n = static_cast<double>(data.size());
  std::cout << "point field " << field.grids().size() << " grids of " << field.spacing() * 100
            << " cm cells, " << field.nodeCount() << " nodes ("
            << field.memoryBytes() / (1024 * 1024) << " MiB), built in " << durationText(build)
            << "; " << rate(static_cast<double>(decided) / n)
            << " of the samples answered by the grids, " << rate(static_cast<double>(fine) / n)
            << " with their " << field.fineBlockCount() << " fine blocks, the rest by exact sums; "
            << equal << " of " << data.size() << " answers equal to the full sum's\n";
  std::cout << "estimate    the grids' estimate alone (answers \"estimate\"): "
            << data.size() - estimateEqual << " of " << data.size()
            << " answers differ from the full sum's; accuracy " << rate(c.accuracy()) << ", TPR "
            << rate(c.tpr()) << " (the full sum's " << rate(full.accuracy()) << ", "
            << rate(full.tpr()) << ")\n";
  return times;
}

/// --original: a joint-space model of one rational-quadratic term, as the original Fastron learns
/// (e.g. `fastron train --data` on the same configurations). Throws InvalidArgument naming the
/// file when it is another kind of model.
Model loadOriginal(const std::string& path) {
  const std::string wanted =
      ": --original takes a joint-space model of one rational-quadratic term (the original "
      "Fastron's: fastron train --data D --features joints), not one of ";
  // The header first: loading a task-space model without its robot would fail with advice about
  // the robot, not about what --original takes.
  if (readModelHeader(path).features != FeatureKind::JointScaling) {
    throw InvalidArgument(path + wanted + "task-space features");
  }
  Model original = loadModel(path);
  if (!OriginalFastronQuery::accepts(original.kernel())) {
    throw InvalidArgument(path + wanted + "kernel " +
                          std::string(toString(original.kernel().type)) + ", " +
                          describeTerms(original.kernel(), original.featureDim()));
  }
  return original;
}

/// The --original model's accuracy and TPR on `data` and its time per configuration with the
/// original's query, against `fastest` (this model's fastest answers, `how`). The two models
/// differ, so their accuracies are printed side by side.
void printAgainstOriginal(const std::string& path, const Model& original, const Dataset& data,
                          double fastest, const std::string& how) {
  const ConfusionCounts c = evaluate(original, data.points, data.labels);
  const OriginalFastronQuery query(original);
  const double seconds = experiments::meanSecondsPerCall(
      data.points, [&](const double* q) { return query.inCollision(q); }, kTimingSeconds);
  std::cout << "against     " << path << ": " << original.supportCount()
            << " support points, accuracy " << rate(c.accuracy()) << ", TPR " << rate(c.tpr())
            << "; " << durationText(seconds)
            << " per configuration with the original Fastron's query: this model (" << how
            << ") is " << times(seconds / fastest) << " faster\n";
}

int runEval(const EvalOptions& o) {
  checkEvalOptions(o);
  std::optional<Robot> robot;
  if (!o.robot.robot.empty()) robot = loadRobotFromOptions(o.robot);
  const Model model = robot ? loadModelFor(o.model, *robot) : loadModel(o.model);
  std::optional<Model> original;
  if (!o.original.empty()) {
    original = loadOriginal(o.original);
    if (original->dim() != model.dim()) {
      throw InvalidArgument(o.original + " has dimension " + std::to_string(original->dim()) +
                            ", but the model " + o.model + " has dimension " +
                            std::to_string(model.dim()));
    }
  }

  Dataset data;
  std::shared_ptr<const SceneChecker> exact;
  if (!o.scene.file.empty() || selfCollisionsAlone(o)) {
    exact = checkerFromOptions(o.scene, *robot, sceneFromOptions(o.scene), "tables      ");
    data = labelledSamples(o, *robot, *exact);
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
  printDataLine(o, data, c, exact.get());
  std::cout << "accuracy    " << rate(c.accuracy()) << "\nTPR         " << rate(c.tpr())
            << "\nTNR         " << rate(c.tnr()) << '\n';
  std::cout << "confusion   TP " << c.truePositives << ", TN " << c.trueNegatives << ", FP "
            << c.falsePositives << ", FN " << c.falseNegatives << '\n';
  if (exact) std::cout << "FN by link  " << missesByLink(model, *exact, data) << '\n';
  std::optional<experiments::Table> alongPath;
  if (exact && (o.clearance || !o.path.empty())) {
    const std::vector<double> clearance = experiments::clearances(*exact, data.points);
    // The batch scores, as evaluate() counts the confusion above: one answer per state.
    const Eigen::VectorXd scores = model.scoreBatch(data.points);
    std::cout << "clearance   free states by distance to the nearest obstacle: "
              << freeStatesByClearance(data, clearance, scores) << '\n';
    if (!o.out.empty()) {
      alongPath = alongPathTable(data, robot->actuatedJointNames(), scores, clearance);
    }
  }
  std::cout << "query time  " << durationText(query) << " per configuration (features "
            << durationText(features) << ", kernel sum "
            << durationText(std::max(0.0, query - features)) << ", " << toString(activeSimdPath())
            << ")\n";
  if (OriginalFastronQuery::accepts(model.kernel())) {
    const OriginalFastronQuery original(model);
    const double seconds = experiments::meanSecondsPerCall(
        data.points, [&](const double* q) { return original.inCollision(q); }, kTimingSeconds);
    std::cout << "original    " << durationText(seconds)
              << " per configuration with the original Fastron's query (Fastron::eval of "
                 "ucsdarclab/fastron, re-implemented): the model is "
              << times(seconds / query) << " faster\n";
  }
  std::optional<double> fieldQuery;
  std::optional<double> estimateQuery;
  if (o.pointField && model.hasOnlyPointTerms()) {
    const FieldTimes field = printPointField(o, model, data, c);
    fieldQuery = field.exact;
    estimateQuery = field.estimate;
    std::cout << "field query " << durationText(field.exact)
              << " per configuration: " << times(query / field.exact)
              << " faster than the full sum; its estimate alone " << durationText(field.estimate)
              << ", " << times(query / field.estimate) << "\n";
  }
  if (original) {
    printAgainstOriginal(o.original, *original, data, fieldQuery.value_or(query),
                         fieldQuery ? "its point field" : "its query");
  }
  if (exact) {
    const double seconds = experiments::meanSecondsPerCheck(data.points, *exact, kTimingSeconds);
    std::cout << std::left << std::setw(12) << "FK+" + exact->name() << durationText(seconds)
              << " per configuration: the model is " << times(seconds / query) << " faster";
    if (fieldQuery) std::cout << ", with its point field " << times(seconds / *fieldQuery);
    if (estimateQuery) std::cout << ", its estimate alone " << times(seconds / *estimateQuery);
    std::cout << '\n';
  }
  if (alongPath) writeAlongPath(o, *alongPath);
  return 0;
}

}  // namespace

void addEvalCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand(
      "eval",
      "Evaluate a model on a labelled dataset, or against an exact checker on a robot in a scene");
  cmd->add_option("--model", o->model, "model file from fastron train")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--data", o->data, "CSV or .npy labelled dataset")->check(CLI::ExistingFile);
  addRobotOptions(*cmd, o->robot, false);
  cmd->add_option("--original", o->original,
                  "a joint-space model of the same robot (fastron train --data D --features "
                  "joints): its accuracy on the same configurations and its time with the "
                  "original Fastron's query, against this model's")
      ->check(CLI::ExistingFile);
  cmd->add_option("--path", o->path,
                  "with --scene: the states along this path (CSV as fastron plan --out writes it) "
                  "instead of uniform samples, with the free states' clearance")
      ->check(CLI::ExistingFile);
  cmd->add_option("--resolution", o->resolution,
                  "with --path: joint-space step between the states checked along each edge "
                  "(default 0.03, as fastron plan's)")
      ->check(numberAbove(0));
  cmd->add_option("--out", o->out,
                  "with --path: folder for along_path.csv (each state: FCL's answer, the model's "
                  "score and answer, the clearance) and along_path.png");
  cmd->add_flag("!--no-plot", o->plot, "with --out: skip the PNG plot");
  addSceneOptions(*cmd, o->scene,
                  {.sceneRequired = false,
                   .selfCollisionHelp =
                       "with --scene: count self-collisions as collisions; with --robot alone: "
                       "against the robot's self-collisions alone (a model of fastron train "
                       "--robot R --self-collision)",
                   .checkerRole = "labels the samples (with --robot and --scene)"});
  cmd->add_flag("--clearance", o->clearance,
                "with --scene: also the free states by distance to the nearest obstacle, and the "
                "share of each the model calls colliding (FCL distances: slow on mesh robots)");
  cmd->add_option("--samples", o->samples, "with --scene: how many samples")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--seed", o->seed, "with --scene: seed of the samples")->capture_default_str();
  cmd->add_flag("!--no-point-field", o->pointField,
                "a model of point terms only: skip its point field (grids that answer without "
                "the full kernel sum)");
  cmd->add_option("--field-spacing", o->field.spacing,
                  "a model of point terms only: cell edge of its point field, metres")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--field-refinement", o->field.refinement,
                  "a model of point terms only: fine cells per cell edge in the fine blocks of its "
                  "point field's least certain cells (1: none)")
      ->capture_default_str()
      ->check(CLI::Range(1, 16));
  cmd->add_option("--field-fine-nodes", o->field.maxFineNodes,
                  "a model of point terms only: the most nodes over its point field's fine blocks")
      ->capture_default_str();
  cmd->callback([o, &exitCode] { exitCode = runEval(*o); });
}

}  // namespace fastron::cli
