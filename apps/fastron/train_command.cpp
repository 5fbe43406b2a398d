// fastron train: Algorithm 1 on a labelled dataset, written as a model file.

#include <algorithm>
#include <iostream>
#include <memory>
#include <numeric>

#include "commands.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model_file.h"
#include "fastron/core/trainer.h"
#include "report_format.h"

namespace fastron::cli {
namespace {

struct TrainOptions {
  std::string data, output, kernel = "rq";
  std::vector<std::string> limits;
  TrainParams params;
  double holdout = 0;
  std::uint64_t seed = 1;
};

/// "lo:hi" per joint, or the dataset's bounding box when none are given.
JointLimits parseLimits(const std::vector<std::string>& items, const Dataset& data) {
  const auto d = static_cast<Eigen::Index>(data.dim());
  if (items.empty()) {
    try {
      return {data.points.colwise().minCoeff().transpose(),
              data.points.colwise().maxCoeff().transpose()};
    } catch (const InvalidArgument& e) {
      throw InvalidArgument(std::string(e.what()) + " in the data's range; give --limits");
    }
  }
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

Dataset rows(const Dataset& data, const std::vector<Eigen::Index>& index) {
  Dataset out;
  out.points.resize(static_cast<Eigen::Index>(index.size()), data.points.cols());
  for (std::size_t k = 0; k < index.size(); ++k) {
    out.points.row(static_cast<Eigen::Index>(k)) = data.points.row(index[k]);
    out.labels.push_back(data.labels[static_cast<std::size_t>(index[k])]);
  }
  return out;
}

int runTrain(const TrainOptions& o) {
  if (o.holdout < 0 || o.holdout >= 1) throw InvalidArgument("--holdout must be in [0, 1)");
  const Dataset data = readDataset(o.data);
  TrainParams params = o.params;
  params.kernel.type = parseKernelType(o.kernel);
  const JointLimits limits = parseLimits(o.limits, data);

  // Split off a random held-out share for validation.
  std::vector<Eigen::Index> order(data.size());
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  Rng rng(o.seed);
  std::shuffle(order.begin(), order.end(), rng);
  const auto held = static_cast<std::size_t>(o.holdout * static_cast<double>(data.size()));
  const Dataset test =
      rows(data, {order.begin(), order.begin() + static_cast<std::ptrdiff_t>(held)});
  const Dataset train =
      rows(data, {order.begin() + static_cast<std::ptrdiff_t>(held), order.end()});

  Trainer trainer(limits, params);
  trainer.addPoints(train.points, train.labels);
  const UpdateReport report = trainer.update();
  const auto model = trainer.model();
  saveModel(*model, o.output);

  std::cout << "data          " << o.data << ": " << data.size() << " configurations, dimension "
            << data.dim() << " (" << train.size() << " for training, " << test.size()
            << " held out)\n";
  std::cout << "joint limits  " << (o.limits.empty() ? "from the data's range:" : "given:");
  for (std::size_t j = 0; j < data.dim(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    std::cout << ' ' << limits.lower()[jj] << ':' << limits.upper()[jj];
  }
  std::cout << "\nkernel        " << toString(params.kernel.type) << ", gamma "
            << params.kernel.gamma << ", beta " << params.beta << '\n';
  std::cout << "update        " << report.iterations
            << " iterations, stopped: " << toString(report.stopReason)
            << (report.reverted ? " (reverted to the better earlier solution)" : "") << ", "
            << duration(seconds(report.elapsed)) << '\n';
  std::cout << "support set   " << report.supportCount << " points; " << report.misclassified
            << " training points misclassified\n";
  if (test.size() > 0) {
    const ConfusionCounts c = evaluate(*model, test.points, test.labels);
    std::cout << "held out      accuracy " << rate(c.accuracy()) << ", TPR " << rate(c.tpr())
              << ", TNR " << rate(c.tnr()) << '\n';
  }
  std::cout << "model         " << o.output << '\n';
  return 0;
}

}  // namespace

void addTrainCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<TrainOptions>();
  CLI::App* cmd =
      app.add_subcommand("train", "Train a Fastron model (Algorithm 1) on a labelled dataset");
  cmd->add_option("--data", o->data, "CSV or .npy: configuration columns, then the label +1 / -1")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "model file to write")->required();
  cmd->add_option("--gamma", o->params.kernel.gamma, "kernel width (input space [-1, 1]^d)")
      ->capture_default_str();
  cmd->add_option("--kernel", o->kernel, "rq (rational quadratic) or gaussian")
      ->capture_default_str();
  cmd->add_option("--beta", o->params.beta, "conditional bias, >= 1")->capture_default_str();
  cmd->add_option("--max-iter", o->params.maxIterations, "iteration limit")->capture_default_str();
  cmd->add_option("--max-support", o->params.maxSupportPoints, "support-point cap")
      ->capture_default_str();
  cmd->add_option(
         "--limits", o->limits,
         "joint limits LOWER:UPPER per column, comma-separated (write --limits=-3.14:3.14,...); "
         "default: the data's range")
      ->delimiter(',');
  cmd->add_option("--holdout", o->holdout, "share of the data held out for validation")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of the held-out split")->capture_default_str();
  cmd->callback([o, &exitCode] { exitCode = runTrain(*o); });
}

}  // namespace fastron::cli
