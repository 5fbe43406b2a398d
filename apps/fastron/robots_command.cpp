// fastron robots: the shipped robots with their joints and limits, and a survey of a robot's
// self-collisions.

#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.h"
#include "fastron/core/error.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/self_collision_survey.h"
#include "robot_options.h"

namespace fastron::cli {
namespace {

/// An actuated joint's kind as its URDF names it (a continuous joint's values are wrapped into
/// the one turn its limits show).
const char* jointKind(JointType type) {
  switch (type) {
    case JointType::Prismatic:
      return "prismatic";
    case JointType::Continuous:
      return "continuous";
    default:
      return "revolute";
  }
}

void describeRobot(const Robot& robot, const std::string& description,
                   const std::filesystem::path& urdf, const std::filesystem::path& srdf,
                   const std::vector<std::pair<std::string, double>>& held) {
  std::cout << robot.name() << ": " << description << '\n';
  std::cout << "  urdf " << urdf.string() << ", " << robot.links().size() << " links, "
            << robot.shapes().size() << " collision shapes\n";
  if (!srdf.empty()) std::cout << "  srdf " << srdf.string() << '\n';
  std::cout << "  link pairs skipped by self-collision checks besides adjacent ones: "
            << robot.allowedCollisions().size() << '\n';
  const JointLimits limits = robot.limits();
  std::cout << "  actuated joints (" << robot.dof() << "):\n";
  for (std::size_t j = 0; j < robot.dof(); ++j) {
    const auto& joint = robot.joints()[static_cast<std::size_t>(robot.actuatedJoints()[j])];
    std::cout << "    " << std::left << std::setw(22) << joint.name << std::setw(12)
              << jointKind(joint.type) << "[" << limits.lower()[static_cast<Eigen::Index>(j)]
              << ", " << limits.upper()[static_cast<Eigen::Index>(j)] << "]\n";
  }
  for (const auto& [joint, value] : held)
    std::cout << "  held: " << joint << " = " << value << '\n';
  std::cout << '\n';
}

/// Every shipped robot, or only the one named; a name that is not shipped is a URDF file, read
/// with the options' package paths and SRDF.
int runRobots(const RobotOptions& options) {
  // The SRDF's planning groups, after the robot: what --group can choose.
  const auto describeGroups = [](const Srdf& srdf) {
    if (srdf.groups.empty()) return;
    std::cout << "  SRDF groups:\n";
    for (const SrdfGroup& g : srdf.groups) {
      std::string joints;
      for (const std::string& j : g.joints) joints += (joints.empty() ? "" : ", ") + j;
      std::cout << "    " << g.name << " (" << g.joints.size()
                << (g.joints.size() == 1 ? " joint" : " joints")
                << (joints.empty() ? "" : ": " + joints) << ")\n";
    }
  };
  bool shown = false;
  for (const RobotEntry& entry : shippedRobots()) {
    if (!options.robot.empty() && entry.name != options.robot) continue;
    const RobotDescription description =
        robotDescriptionFromOptions({.robot = entry.name,
                                     .joints = {},
                                     .packagePaths = options.packagePaths,
                                     .srdf = options.srdf,
                                     .group = options.group});
    describeRobot(description.robot, entry.description, entry.urdf,
                  options.srdf.empty() ? entry.srdf : std::filesystem::path(options.srdf),
                  entry.held);
    if (!options.robot.empty()) describeGroups(description.srdf);
    shown = true;
  }
  if (!shown) {
    const RobotDescription description = robotDescriptionFromOptions(options);
    describeRobot(description.robot, "a URDF file", options.robot, options.srdf, {});
    describeGroups(description.srdf);
  }
  return 0;
}

std::string percent(std::size_t count, std::size_t of) {
  char text[16];
  std::snprintf(text, sizeof text, "%.1f%%",
                100.0 * static_cast<double>(count) / static_cast<double>(of));
  return text;
}

int runSurvey(const RobotOptions& robotOptions, const SelfCollisionOptions& options) {
  const Robot robot = loadRobotFromOptions(robotOptions);
  std::cerr << "sampling " << options.samples << " configurations of " << robot.name() << "...\n";
  const SelfCollisionSurvey survey = surveySelfCollisions(robot, options);
  std::cout << robot.name() << ": self-collisions over " << survey.samples
            << " uniform configurations (FCL; adjacent and already allowed pairs skipped)\n"
            << "  configurations with any pair touching      "
            << percent(survey.configurationsBefore, survey.samples) << '\n'
            << "  ... with an enabled pair touching          "
            << percent(survey.configurationsInCollision, survey.samples) << "\n\n";
  if (survey.pairs.empty()) {
    std::cout << "  no link pairs to check: every pair is adjacent or allowed\n";
    return 0;
  }
  std::size_t never = 0;
  std::cout << "  " << std::left << std::setw(52) << "link pair" << std::setw(10) << "collides"
            << std::setw(9) << "at home"
            << "verdict\n";
  for (const LinkPairSurvey& p : survey.pairs) {
    if (p.verdict == PairVerdict::Never) {
      ++never;
      continue;
    }
    std::cout << "  " << std::setw(52) << (p.linkA + " / " + p.linkB) << std::setw(10)
              << percent(p.collisions, survey.samples) << std::setw(9) << (p.atHome ? "yes" : "no")
              << toString(p.verdict) << '\n';
  }
  if (never > 0) std::cout << "  ... and " << never << " pairs that never collided (never)\n";

  std::cout << "\nPairs MoveIt Setup Assistant would disable (default: touching at the home "
               "configuration; always: in at least "
            << options.alwaysShare * 100
            << "% of the samples; never: in none of them, which only saves checking time, and more "
               "--samples make surer), for "
               "robots.yaml's allowed_collisions or an SRDF's disable_collisions:\n";
  std::size_t listed = 0;
  for (const LinkPairSurvey& p : survey.pairs) {
    if (p.verdict == PairVerdict::Enabled) continue;
    std::cout << "  - [" << p.linkA << ", " << p.linkB << "]  # " << toString(p.verdict) << '\n';
    ++listed;
  }
  if (listed == 0) std::cout << "  (none)\n";
  return 0;
}

}  // namespace

void addRobotsCommand(CLI::App& app, int& exitCode) {
  auto only = std::make_shared<std::string>();
  auto survey = std::make_shared<bool>(false);
  auto options = std::make_shared<SelfCollisionOptions>();
  CLI::App* cmd =
      app.add_subcommand("robots", "List the shipped robots with their joints and limits");
  cmd->add_option("name", *only, "show only this robot (with --self-collisions: or a URDF file)");
  cmd->add_flag("--self-collisions", *survey,
                "survey which link pairs collide, as MoveIt Setup Assistant does");
  cmd->add_option("--samples", options->samples, "configurations sampled by the survey")
      ->check(numberAbove(0))
      ->capture_default_str();
  cmd->add_option("--seed", options->seed, "random seed of the survey")->capture_default_str();
  auto files = std::make_shared<RobotOptions>();  // the robot is the positional name
  cmd->add_option("--package-path", files->packagePaths,
                  "folder searched for package:// and relative mesh paths (repeatable)");
  cmd->add_option("--srdf", files->srdf,
                  "MoveIt SRDF: its disable_collisions pairs are skipped (and not surveyed), its "
                  "groups listed");
  cmd->add_option("--group", files->group, "an SRDF group whose joints are actuated");
  cmd->callback([only, survey, options, files, &exitCode] {
    files->robot = *only;
    if (*survey) {
      if (only->empty()) throw InvalidArgument("--self-collisions needs a robot name or URDF file");
      exitCode = runSurvey(*files, *options);
      return;
    }
    if (only->empty() && (!files->srdf.empty() || !files->group.empty()))
      throw InvalidArgument("--srdf and --group need a robot name or URDF file");
    exitCode = runRobots(*files);
  });
}

}  // namespace fastron::cli
