// fastron eval: a model against a labelled dataset.

#include <chrono>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model_file.h"
#include "report_format.h"

namespace fastron::cli {
namespace {

struct EvalOptions {
  std::string model, data;
};

int runEval(const EvalOptions& o) {
  const Dataset data = readDataset(o.data);
  const Model model = loadModel(o.model);
  if (model.dim() != data.dim()) {
    throw InvalidArgument(o.data + " has " + std::to_string(data.dim()) +
                          " configuration columns, but the model " + o.model + " has dimension " +
                          std::to_string(model.dim()));
  }
  const ConfusionCounts c = evaluate(model, data.points, data.labels);

  // Query time: the dataset's configurations, one at a time, repeated to at least 0.2 s.
  using Clock = std::chrono::steady_clock;
  std::size_t queries = 0;
  volatile double sink = 0;  // keeps the queries from being optimised away
  const auto start = Clock::now();
  while (Clock::now() - start < std::chrono::milliseconds(200)) {
    for (Eigen::Index i = 0; i < data.points.rows(); ++i)
      sink = sink + model.score(data.points.row(i).data());
    queries += data.size();
  }
  const double perQuery =
      std::chrono::duration<double>(Clock::now() - start).count() / static_cast<double>(queries);

  std::cout << "model       " << o.model << ": dimension " << model.dim() << ", "
            << model.supportCount() << " support points, kernel " << toString(model.kernel().type)
            << " gamma " << model.kernel().gamma << '\n';
  std::cout << "data        " << o.data << ": " << data.size() << " configurations\n";
  std::cout << "accuracy    " << rate(c.accuracy()) << "\nTPR         " << rate(c.tpr())
            << "\nTNR         " << rate(c.tnr()) << '\n';
  std::cout << "confusion   TP " << c.truePositives << ", TN " << c.trueNegatives << ", FP "
            << c.falsePositives << ", FN " << c.falseNegatives << '\n';
  std::cout << "query time  " << duration(perQuery) << " per configuration (mean of " << queries
            << ")\n";
  return 0;
}

}  // namespace

void addEvalCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand("eval", "Evaluate a model on a labelled dataset");
  cmd->add_option("--model", o->model, "model file from fastron train")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--data", o->data, "CSV or .npy labelled dataset")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->callback([o, &exitCode] { exitCode = runEval(*o); });
}

}  // namespace fastron::cli
