// fastron demo: a planar two-link arm among discs that move on circles. Its C-space is 2-D and
// its oracle analytic, so the learned boundary can be drawn against the exact one.

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <numbers>

#include "commands.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model_file.h"
#include "fastron/experiments/common.h"
#include "fastron/proxy/labelling.h"
#include "fastron/proxy/proxy_collision_detector.h"
#include "plotting.h"
#include "report_format.h"

namespace fastron::cli {
namespace {

using std::numbers::pi;

struct DemoOptions {
  std::string out = "fastron-demo";
  std::size_t steps = 40, initialPoints = 2000, testPoints = 5000;
  double gamma = 30, beta = 5;
  std::size_t maxIterations = 20000;
  std::size_t activeLearning = 500, kappa = 5;
  std::uint64_t seed = 1;
  bool plot = true;
};

/// The arm's base is at the origin; a configuration is (theta1, theta2) in [-pi, pi]^2.
class PlanarArmWorld {
 public:
  struct Disc {
    Eigen::Vector2d orbitCentre;
    double orbitRadius, radius, speed, phase;
    Eigen::Vector2d centre{0, 0};
  };

  PlanarArmWorld()
      : discs_{{{1.1, 0.6}, 0.35, 0.25, 0.15, 0.0},
               {{-0.9, -0.9}, 0.40, 0.30, -0.10, 1.0},
               {{0.2, -1.3}, 0.30, 0.20, 0.20, 2.0},
               {{-0.7, 1.0}, 0.25, 0.22, 0.12, 4.0}} {
    setTime(0);
  }

  /// Moves every disc to its place on its circle at step t.
  void setTime(double t) {
    for (Disc& d : discs_) {
      const double a = d.phase + d.speed * t;
      d.centre = d.orbitCentre + d.orbitRadius * Eigen::Vector2d(std::cos(a), std::sin(a));
    }
  }

  bool inCollision(const double* q) const {
    const Eigen::Vector2d elbow = kLink1 * Eigen::Vector2d(std::cos(q[0]), std::sin(q[0]));
    const Eigen::Vector2d hand =
        elbow + kLink2 * Eigen::Vector2d(std::cos(q[0] + q[1]), std::sin(q[0] + q[1]));
    for (const Disc& d : discs_) {
      const double reach = d.radius + kLinkRadius;
      if (segmentDistance(Eigen::Vector2d::Zero(), elbow, d.centre) < reach ||
          segmentDistance(elbow, hand, d.centre) < reach) {
        return true;
      }
    }
    return false;
  }

  const std::vector<Disc>& discs() const { return discs_; }
  static constexpr double kLink1 = 1.0, kLink2 = 0.8, kLinkRadius = 0.05;

 private:
  static double segmentDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                const Eigen::Vector2d& p) {
    const Eigen::Vector2d ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (a + t * ab - p).norm();
  }

  std::vector<Disc> discs_;
};

std::ofstream openOutput(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw FileError(path.string() + ": cannot write");
  return out;
}

void writeSnapshot(const std::filesystem::path& dir, const PlanarArmWorld& world,
                   const Model& model) {
  constexpr int kGrid = 241;
  std::ofstream grid = openOutput(dir / "cspace_grid.csv");
  grid << "theta1,theta2,in_collision,score\n" << std::setprecision(6);
  for (int a = 0; a < kGrid; ++a) {
    for (int b = 0; b < kGrid; ++b) {
      const double q[2] = {-pi + 2 * pi * a / (kGrid - 1), -pi + 2 * pi * b / (kGrid - 1)};
      grid << q[0] << ',' << q[1] << ',' << world.inCollision(q) << ',' << model.score(q) << '\n';
    }
  }
  std::ofstream support = openOutput(dir / "support_points.csv");
  support << "theta1,theta2,weight\n" << std::setprecision(8);
  const Configurations joints = model.limits().toJoint(Configurations(model.supportPoints()));
  for (Eigen::Index i = 0; i < joints.rows(); ++i) {
    support << joints(i, 0) << ',' << joints(i, 1) << ',' << model.weights()[i] << '\n';
  }
  std::ofstream discs = openOutput(dir / "discs.csv");
  discs << "x,y,radius\n";
  for (const auto& d : world.discs())
    discs << d.centre.x() << ',' << d.centre.y() << ',' << d.radius << '\n';
}

int runDemo(const DemoOptions& o) {
  const std::filesystem::path dir = o.out;
  std::filesystem::create_directories(dir);
  PlanarArmWorld world;
  auto oracle = std::make_shared<FunctionChecker>(
      "planar arm among discs", 2, [&world](const double* q) { return world.inCollision(q); });
  const JointLimits limits(Eigen::Vector2d(-pi, -pi), Eigen::Vector2d(pi, pi));
  ProxyParams params;
  params.train.kernel.gamma = o.gamma;
  params.train.beta = o.beta;
  params.train.maxIterations = o.maxIterations;
  params.activeLearning = {o.activeLearning, o.kappa, 0};
  params.seed = o.seed;
  ProxyCollisionDetector proxy(oracle, limits, params);
  Rng testRng(o.seed + 1);

  std::cout << "Fastron demo: planar 2-link arm, " << world.discs().size()
            << " discs moving on circles, " << o.steps << " steps\n";
  std::cout << "gamma " << o.gamma << ", beta " << o.beta << ", " << o.initialPoints
            << " initial points, " << o.activeLearning
            << " active-learning points per step; accuracy on " << o.testPoints
            << " fresh configurations per step\n\n";
  const char* header =
      "step  |S|   labels  update ms  label ms  train ms  accuracy  TPR     TNR     stop\n";
  std::cout << header;
  std::ofstream steps = openOutput(dir / "steps.csv");
  steps << "step,support,labelled,update_ms,label_ms,train_ms,iterations,stop,accuracy,tpr,tnr\n";
  std::ofstream report = openOutput(dir / "report.md");
  report << "# Fastron demo\n\nPlanar two-link arm among " << world.discs().size()
         << " moving discs. Command: `fastron demo --steps " << o.steps << " --seed " << o.seed
         << "`.\n\n"
         << "| step | support points | labels | update (ms) | accuracy | TPR | TNR "
            "|\n|---|---|---|---|---|---|---|\n";

  Dataset test;  // fresh labelled configurations of the current step
  test.columnNames = {"theta1", "theta2"};
  for (std::size_t t = 0; t <= o.steps; ++t) {
    world.setTime(static_cast<double>(t));
    const StepReport r = t == 0 ? proxy.initialize(o.initialPoints) : proxy.step();
    test.points = uniformConfigurations(limits, o.testPoints, testRng);
    test.labels = labelConfigurations(*oracle, test.points);
    const ConfusionCounts c = evaluate(*proxy.model(), test.points, test.labels);
    const double updateMs = seconds(r.total) * 1e3, labelMs = seconds(r.labelTime) * 1e3;
    const double trainMs = seconds(r.update.elapsed) * 1e3;
    std::cout << std::left << std::setw(6) << t << std::setw(6) << r.update.supportCount
              << std::setw(8) << r.labelled << std::fixed << std::setprecision(2) << std::setw(11)
              << updateMs << std::setw(10) << labelMs << std::setw(10) << trainMs << std::setw(10)
              << rate(c.accuracy()) << std::setw(8) << rate(c.tpr()) << std::setw(8)
              << rate(c.tnr()) << toString(r.update.stopReason) << '\n'
              << std::flush;
    steps << t << ',' << r.update.supportCount << ',' << r.labelled << ',' << updateMs << ','
          << labelMs << ',' << trainMs << ',' << r.update.iterations << ','
          << toString(r.update.stopReason) << ',' << c.accuracy() << ',' << c.tpr() << ','
          << c.tnr() << '\n';
    report << "| " << t << " | " << r.update.supportCount << " | " << r.labelled << " | "
           << updateMs << " | " << rate(c.accuracy()) << " | " << rate(c.tpr()) << " | "
           << rate(c.tnr()) << " |\n";
  }

  const auto model = proxy.model();
  const Configurations probe = uniformConfigurations(limits, 20000, testRng);
  const double modelTime = meanSecondsPerCall(
      probe, [&](const double* q) { return model->inCollision(q); }, 0.1);
  const double oracleTime = meanSecondsPerCall(
      probe, [&](const double* q) { return world.inCollision(q); }, 0.1);
  std::cout << "\nquery time: Fastron " << duration(modelTime) << " (" << model->supportCount()
            << " support points), analytic oracle " << duration(oracleTime) << '\n';
  report << "\nQuery time: Fastron " << duration(modelTime) << " with " << model->supportCount()
         << " support points; the analytic oracle " << duration(oracleTime)
         << " (an analytic 2-D oracle is cheaper than any learned model: the point of Fastron is "
            "replacing forward kinematics plus geometric checks).\n";

  saveModel(*model, dir / "model.fastron");
  writeCsv(test, dir / "test_points.csv");
  writeSnapshot(dir, world, *model);
  steps.close();
  report.close();
  if (o.plot) {
    const std::string error = runPlotScript("plot_demo.py", {dir.string()});
    if (!error.empty()) std::cerr << "fastron: warning: no plots drawn: " << error << '\n';
  }
  std::cout << "results in " << dir.string()
            << "/: steps.csv, report.md, model.fastron, cspace_grid.csv, "
            << "support_points.csv, test_points.csv" << (o.plot ? ", cspace.png, steps.png" : "")
            << '\n';
  return 0;
}

}  // namespace

void addDemoCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<DemoOptions>();
  CLI::App* cmd =
      app.add_subcommand("demo", "Learn the C-space of a planar arm among moving discs");
  cmd->add_option("--out", o->out, "output folder")->capture_default_str();
  cmd->add_option("--steps", o->steps, "obstacle motions (model updates) after the first model")
      ->capture_default_str();
  cmd->add_option("--initial", o->initialPoints, "initial uniform training points")
      ->capture_default_str();
  cmd->add_option("--test", o->testPoints, "fresh configurations scored per step")
      ->capture_default_str();
  cmd->add_option("--gamma", o->gamma, "kernel width")->capture_default_str();
  cmd->add_option("--beta", o->beta, "conditional bias")->capture_default_str();
  cmd->add_option("--max-iter", o->maxIterations, "iteration limit per update")
      ->capture_default_str();
  cmd->add_option("--active", o->activeLearning, "active-learning points per step (A_max)")
      ->capture_default_str();
  cmd->add_option("--kappa", o->kappa, "exploitation samples per support point")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed of every random choice")->capture_default_str();
  cmd->add_flag("!--no-plot", o->plot, "skip the PNG plots");
  cmd->callback([o, &exitCode] { exitCode = runDemo(*o); });
}

}  // namespace fastron::cli
