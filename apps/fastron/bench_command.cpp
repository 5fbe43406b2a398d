// fastron bench NAME: one of the paper's experiments; raw results as CSV, the paper's tables as
// Markdown with the paper's values beside ours, and the paper's figures as PNG.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/error.h"
#include "fastron/experiments/changing_experiment.h"
#include "fastron/experiments/cspace_experiment.h"
#include "fastron/experiments/static_experiment.h"
#include "plotting.h"

namespace fastron::cli {
namespace {

struct BenchOptions {
  std::string name, out;
  std::size_t trials = 0;  // 0: the experiment's default
  std::uint64_t seed = 1;
  bool quick = false, plot = true;
};

int runBench(const BenchOptions& o) {
  const std::filesystem::path dir = o.out.empty()
                                        ? std::filesystem::path("fastron-results") / o.name
                                        : std::filesystem::path(o.out);
  std::filesystem::create_directories(dir);
  const auto start = std::chrono::steady_clock::now();
  const Progress progress = [start](std::string_view line) {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[" << static_cast<int>(s) << " s] " << line << std::endl;
  };

  Table results;
  std::string report;
  StaticOptions options;
  options.seed = o.seed;
  options.quick = o.quick;
  if (o.name == "static") {
    options.trials = o.trials ? o.trials : (o.quick ? 1 : 10);
    results = runStatic(options, progress);
    report = staticReport(results, options);
  } else if (o.name == "static-beta" || o.name == "static-gamma") {
    options.trials = o.trials ? o.trials : (o.quick ? 1 : 10);
    const std::string parameter = o.name.substr(7);
    results = runStaticSweep(options, parameter, progress);
    report = staticSweepReport(results, parameter, options);
  } else if (o.name == "changing") {
    ChangingOptions changing;
    changing.trials = o.trials ? o.trials : (o.quick ? 1 : 3);
    changing.steps = o.quick ? 3 : 50;
    changing.seed = o.seed;
    changing.quick = o.quick;
    if (o.quick) changing.cases = {"4dof", "7dof-3boxes"};
    results = runChanging(changing, progress);
    report = changingReport(results, changing);
  } else if (o.name == "sweep") {
    SweepOptions sweep;
    sweep.trials = o.trials ? o.trials : (o.quick ? 1 : 3);
    sweep.seed = o.seed;
    sweep.quick = o.quick;
    if (o.quick) sweep.obstacles = {1, 10};
    results = runObstacleSweep(sweep, progress);
    report = sweepReport(results, sweep);
  } else if (o.name == "cspace") {
    const CspaceOptions cspace{o.trials ? o.trials : (o.quick ? 1u : 3u), o.seed, o.quick};
    const CspaceResults r = runCspace(cspace, progress);
    results = r.summary;
    r.grid.writeCsv(dir / "grid.csv");
    r.support.writeCsv(dir / "support.csv");
    r.cubes.writeCsv(dir / "cubes.csv");
    report = cspaceReport(r, cspace);
  } else {
    throw InvalidArgument("unknown experiment '" + o.name + "'");
  }

  results.writeCsv(dir / "results.csv");
  std::ofstream(dir / "report.md") << report;
  std::cout << '\n' << report << '\n';
  if (o.plot) {
    const std::string error = runPlotScript("plot_experiments.py", {o.name, dir.string()});
    if (!error.empty()) std::cerr << "fastron: warning: no plots drawn: " << error << '\n';
  }
  std::cout << "results in " << dir.string() << "/: results.csv, report.md"
            << (o.plot ? ", " + o.name + ".png" : "") << '\n';
  return 0;
}

}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Run one of the paper's experiments");
  cmd->add_option("name", o->name, "static, static-beta, static-gamma, cspace, changing, sweep")
      ->required()
      ->check(
          CLI::IsMember({"static", "static-beta", "static-gamma", "cspace", "changing", "sweep"}));
  cmd->add_option("--trials", o->trials,
                  "trials (random environments); default: the experiment's own");
  cmd->add_option("--seed", o->seed, "seed of every random choice")->capture_default_str();
  cmd->add_option("--out", o->out, "output folder (default: fastron-results/NAME)");
  cmd->add_flag("--quick", o->quick, "small sizes, for a fast check");
  cmd->add_flag("!--no-plot", o->plot, "skip the PNG plots");
  cmd->callback([o, &exitCode] { exitCode = runBench(*o); });
}

}  // namespace fastron::cli
