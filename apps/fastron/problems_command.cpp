// fastron problems: planning problems in MotionBenchMaker's file format, generated.

#include <chrono>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/experiments/problem_families.h"
#include "fastron/experiments/sensed_problems.h"
#include "robot_options.h"

namespace fastron::cli {
namespace {

struct ProblemsCommandOptions {
  RobotOptions robot;
  std::string family = "cage", output, tipLink, from;
  double sensed = 0, radius = 0, solvable = 0;
  std::size_t count = 10, samples = experiments::ProblemOptions{}.samplesPerAttempt;
  std::uint64_t seed = 1;
  bool noSelfCollision = false;
};

/// --from DIR --sensed S: an existing family's scenes as clouds.
int convertProblems(const ProblemsCommandOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t written = experiments::writeSensedProblems(
      o.from, o.output, {.spacing = o.sensed, .radius = o.radius, .seed = o.seed});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "wrote " << written << " sensed scenes (sceneNNNN.yaml with sceneNNNN.npy, surfaces "
            << "sampled every " << o.sensed << " m) and their requests to " << o.output << " ("
            << seconds << " s)\n";
  return 0;
}

int runProblems(const ProblemsCommandOptions& o) {
  if (!o.from.empty()) {
    if (o.sensed <= 0) throw InvalidArgument("--from converts problems: give --sensed SPACING");
    return convertProblems(o);
  }
  if (o.robot.robot.empty())
    throw InvalidArgument("--robot is required (or --from DIR --sensed S)");
  const RobotDescription description = robotDescriptionFromOptions(o.robot);
  const Robot& robot = description.robot;
  // The requests name the SRDF group that moves these joints, as MoveIt's requests do.
  std::string group = o.robot.group;
  for (const SrdfGroup& g : description.srdf.groups) {
    if (group.empty() && g.joints == robot.actuatedJointNames()) group = g.name;
  }
  if (group.empty()) group = "arm";
  experiments::ProblemOptions options;
  options.family = experiments::parseProblemFamily(o.family);
  options.count = o.count;
  options.seed = o.seed;
  options.selfCollision = !o.noSelfCollision;
  options.tipLink = o.tipLink;
  options.samplesPerAttempt = o.samples;
  options.solvableWithin = o.solvable;
  const auto start = std::chrono::steady_clock::now();
  const auto problems = experiments::generateProblems(robot, options);
  experiments::writeProblems(o.output, robot, problems, group);
  if (o.sensed > 0) {
    experiments::writeSensedProblems(o.output, o.output,
                                     {.spacing = o.sensed, .radius = o.radius, .seed = o.seed});
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "wrote " << problems.size() << " '" << o.family << "' problems for " << robot.name()
            << " to " << o.output << " (sceneNNNN.yaml, requestNNNN.yaml; " << seconds << " s"
            << (o.sensed > 0 ? ", obstacles as sensed clouds" : "")
            << "); plan them with: fastron bench motion-bench --problems " << o.output
            << " --robot " << o.robot.robot;
  // The same robot files, and self-collision checked as the ends were chosen free of it.
  if (!o.robot.srdf.empty()) std::cout << " --srdf " << o.robot.srdf;
  for (const std::string& dir : o.robot.packagePaths) std::cout << " --package-path " << dir;
  std::cout << (o.noSelfCollision ? "" : " --self-collision") << "\n";
  return 0;
}

}  // namespace

void addProblemsCommand(CLI::App& app, int& exitCode) {
  auto o = std::make_shared<ProblemsCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "problems",
      "Write generated planning problems (MoveIt scene and request files, MotionBenchMaker's "
      "format): the robot reaches into a cage or an open box placed anew for each problem");
  addRobotOptions(*cmd, o->robot, false);  // --group: also the requests' group_name (default: the
                                           // SRDF group of the actuated joints, else "arm")
  cmd->add_option("--family", o->family, "cage or box")
      ->capture_default_str()
      ->check(CLI::IsMember({"cage", "box"}));
  cmd->add_option("-n,--count", o->count, "how many problems")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option("-o,--output", o->output, "folder to write them to (created)")->required();
  cmd->add_option("--seed", o->seed, "seed of the placements, starts and goals")
      ->capture_default_str();
  cmd->add_option("--samples", o->samples,
                  "uniform configurations drawn per try at a goal or a start (20 placements of the "
                  "structure are tried)")
      ->capture_default_str()
      ->check(numberAbove(0));
  cmd->add_option(
      "--tip-link", o->tipLink,
      "link whose origin reaches the object (default: of the child of the last actuated joint "
      "and the links fixed to it, the farthest from it, e.g. panda_grasptarget)");
  cmd->add_option("--solvable", o->solvable,
                  "keep a problem only when RRT-Connect on FCL plans it within this many seconds "
                  "(otherwise the structure is placed anew; default 0: no plan)")
      ->check(numberAbove(0, true));
  cmd->add_flag("--no-self-collision", o->noSelfCollision,
                "start and goal need not be free of the robot's collisions with itself");
  cmd->add_option("--sensed", o->sensed,
                  "write each scene's obstacles as a point cloud instead: their surfaces sampled "
                  "this many metres apart (sceneNNNN.npy beside sceneNNNN.yaml)")
      ->check(numberAbove(0));
  cmd->add_option("--radius", o->radius,
                  "with --sensed: the radius of each point's ball (default: the spacing)")
      ->check(numberAbove(0, true));
  cmd->add_option("--from", o->from,
                  "with --sensed: convert the problems of this folder (e.g. a MotionBenchMaker "
                  "family) instead of generating new ones; the robot options are not needed")
      ->check(CLI::ExistingDirectory);
  cmd->callback([o, &exitCode] { exitCode = runProblems(*o); });
}

}  // namespace fastron::cli
