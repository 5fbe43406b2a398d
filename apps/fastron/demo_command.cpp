// fastron demo: the paper in one run. Baxter's 7-joint arm among three moving boxes; the model
// updates in the background while RRT-Connect replans with Fastron, GJK and FCL.

#include <ompl/util/RandomNumbers.h>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/dataset.h"
#include "fastron/core/model_file.h"
#include "fastron/experiments/demo_experiment.h"
#include "plotting.h"
#include "report_format.h"
#include "robot_options.h"

namespace fastron::cli {

using namespace experiments;  // the command runs the experiments layer
namespace {

struct DemoCommandOptions {
  std::string out = "fastron-demo";
  DemoOptions demo;
  std::string features = "fk";
  bool plot = true;
};

int runDemoCommand(DemoCommandOptions o) {
  o.demo.features = parseFeatureKind(o.features);
  const std::filesystem::path dir(o.out);
  std::filesystem::create_directories(dir);
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(o.demo.seed));
  std::cout << "Fastron demo: Baxter's right arm (7 joints) among three boxes on random walks\n";
  const DemoResults results = runDemo(o.demo, progressPrinter());

  const std::string report = demoReport(results, o.demo);
  std::cout << '\n' << report << '\n';
  results.ticks.table().writeCsv(dir / "ticks.csv");
  std::ofstream(dir / "report.md") << report;
  saveModel(*results.model, dir / "model.fastron");
  writeCsv(results.test, dir / "test_points.csv");
  if (o.plot) {
    const std::string error = runPlotScript("plot_demo.py", {dir.string()});
    if (!error.empty()) std::cerr << "fastron: warning: no plots drawn: " << error << '\n';
  }
  std::cout
      << "results in " << dir.string()
      << "/: report.md, ticks.csv, model.fastron (the model of the last tick), test_points.csv "
         "(its FCL-labelled test configurations)"
      << (o.plot ? ", demo.png" : "") << '\n';
  // The guarantee the demo shows: no final path collides under FCL.
  for (const PlanRow& row : results.ticks.rows) {
    if (row.outcome.collidesUnderAudit.value_or(false)) {
      std::cerr << "fastron: error: a final path collides under FCL\n";
      return 1;
    }
  }
  return 0;
}

}  // namespace

void addDemoCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<DemoCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "demo", "Baxter among moving boxes: background model updates and RRT-Connect replanning");
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->add_option("--ticks", o->demo.ticks, "obstacle moves, each with a fresh planning query")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--tick", o->demo.tickSeconds, "shortest tick (s): the pace of the boxes")
      ->capture_default_str()
      ->check(numberAbove(0, true));
  cmd->add_option("--initial", o->demo.initialPoints, "samples of the first model")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--test", o->demo.testPoints, "fresh configurations scoring the model per tick")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--time-limit", o->demo.timeLimit, "seconds per planning query")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--resolution", o->demo.resolution, "joint-space step of edge checks (rad)")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("--model-resolution", o->demo.modelResolution,
                  "joint-space step of edge checks on the model or its hybrid (rad; default: 3 "
                  "times --resolution; their paths are verified with FCL at --resolution)")
      ->check(numberAbove(0));
  cmd->add_option("--learn-from-verification", o->demo.learnFromVerification,
                  "feed the exact answers of verification and repair to the model's next update")
      ->capture_default_str();
  cmd->add_option("--simplify-time", o->demo.simplifyTime,
                  "seconds of OMPL path simplification per plan, every checker alike (0: off)")
      ->capture_default_str()
      ->check(numberAbove(0, true));
  addSimplificationOption(*cmd, [o](PathSimplification s) { o->demo.simplification = s; });
  cmd->add_option("--kernel-whole-share", o->demo.wholeShare,
                  "fk: the whole feature vector's share of the kernel (default 0.5); 0: point "
                  "terms alone, answered by a point field")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option_function<std::string>(
         "--field-answers",
         [o](const std::string& text) { o->demo.fieldAnswers = parseFieldAnswers(text); },
         "with --kernel-whole-share 0: what the point field answers where its grids leave the "
         "sign undecided: exact (the full sum's sign) or estimate (the grids' estimate alone)")
      ->check(CLI::IsMember({"exact", "estimate"}));
  cmd->add_option("--gamma", o->demo.gamma, "fk: kernel width (default 40)")->check(numberAbove(0));
  cmd->add_option("--beta", o->demo.beta, "conditional bias of the models (default: the case's)")
      ->check(numberAbove(0, true));
  cmd->add_option("--control-points", o->demo.controlPoints.maxPoints,
                  "fk: at most this many automatic control points (0: all)")
      ->capture_default_str();
  cmd->add_option("--control-per-body", o->demo.controlPoints.maxPerBody,
                  "fk: at most this many automatic control points on one rigid body (0: no limit)")
      ->capture_default_str();
  cmd->add_flag("--control-geometry", o->demo.controlPoints.alongGeometry,
                "fk: automatic control points may also lie along each link's collision geometry "
                "(its bounding box's centre and the ends of its longest side): for "
                "--kernel-whole-share 0");
  cmd->add_option("--band-miss-rate", o->demo.band.missRate,
                  "Hybrid: colliding configurations the model may answer free (calibrated rate)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--band-false-alarm-rate", o->demo.band.falseAlarmRate,
                  "Hybrid: free configurations the model may answer colliding (calibrated rate)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--seed", o->demo.seed, "seed of every random choice")->capture_default_str();
  addFeatureKindOption(*cmd, o->features);
  cmd->add_flag("!--no-plot", o->plot, "skip the PNG plots");
  cmd->callback([o, &exitCode] { exitCode = runDemoCommand(*o); });
}

}  // namespace fastron::cli
