#include "robot_options.h"

#include <iostream>
#include <map>

#include "fastron/core/error.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"

namespace fastron::cli {

void addRobotOptions(CLI::App& cmd, RobotOptions& options, bool required) {
  cmd.add_option("--robot", options.robot, "a shipped robot (see fastron robots) or a URDF file")
      ->required(required);
  cmd.add_option(
         "--joints", options.joints,
         "actuated joints, comma-separated (default: the robot's own list); others stay at 0")
      ->delimiter(',');
  cmd.add_option("--package-path", options.packagePaths,
                 "folder searched for package:// and relative mesh paths (repeatable)");
  cmd.add_option("--srdf", options.srdf,
                 "MoveIt SRDF: its disable_collisions pairs are skipped in self-collision checks, "
                 "its groups can be chosen with --group");
  cmd.add_option("--group", options.group,
                 "an SRDF group whose joints are actuated (instead of --joints)");
}

Robot loadRobotFromOptions(const RobotOptions& options) {
  return robotDescriptionFromOptions(options).robot;
}

RobotDescription robotDescriptionFromOptions(const RobotOptions& options) {
  if (!options.group.empty() && !options.joints.empty())
    throw InvalidArgument("give --group or --joints, not both");
  UrdfOptions urdf;
  for (const auto& p : options.packagePaths) urdf.searchPaths.emplace_back(p);
  RobotDescription description = loadRobotDescription(options.robot, urdf, options.srdf);
  for (const std::string& w : description.warnings) std::cerr << "fastron: warning: " << w << '\n';
  Robot& robot = description.robot;
  if (!options.joints.empty()) robot.setActuatedJoints(options.joints);
  if (!options.group.empty()) robot.setActuatedJoints(description.srdf.group(options.group).joints);
  return description;
}

Eigen::VectorXd configurationFromOption(const std::vector<double>& values, const Robot& robot,
                                        const char* option) {
  if (values.size() != robot.dof()) {
    std::string names;
    for (const auto& n : robot.actuatedJointNames()) names += (names.empty() ? "" : ", ") + n;
    throw InvalidArgument(std::string(option) + " has " + std::to_string(values.size()) +
                          " values but " + robot.name() + " has " + std::to_string(robot.dof()) +
                          " actuated joints (" + names + ")");
  }
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

void addFeatureKindOption(CLI::App& cmd, std::string& kind) {
  cmd.add_option("--features", kind,
                 "Fastron's input: fk (world positions of control points on the robot) or "
                 "joints (scaled joint values, as in the paper)")
      ->capture_default_str()
      ->check(CLI::IsMember({"fk", "joints"}));
}

void addFeatureOptions(CLI::App& cmd, FeatureOptions& options) {
  addFeatureKindOption(cmd, options.kind);
  cmd.add_option("--control-links", options.controlLinks,
                 "fk: control points, comma-separated: LINK (the link's origin) or LINK@X:Y:Z (a "
                 "point in the link's frame, metres); default: chosen automatically, see "
                 "docs/algorithms.md")
      ->delimiter(',');
  cmd.add_option("--control-points", options.automatic.maxPoints,
                 "fk: at most this many automatic control points (0: all)")
      ->capture_default_str();
  cmd.add_option("--control-spacing", options.automatic.minSpacing,
                 "fk: automatic control points at least this far apart on average (m)")
      ->capture_default_str();
  cmd.add_option("--control-per-body", options.automatic.maxPerBody,
                 "fk: at most this many automatic control points on one rigid body (0: no limit)")
      ->capture_default_str();
  cmd.add_flag("--control-geometry", options.automatic.alongGeometry,
               "fk: automatic control points may also lie along each link's collision geometry "
               "(its bounding box's centre and the ends of its longest side), not only at link "
               "origins: for --kernel-whole-share 0");
  cmd.add_option("--control-rule", options.automatic.rule,
                 "fk: how automatic control points are chosen: spread (the points that move "
                 "most) or cover (spread along the chain)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, ControlPointRule>{
          {"spread", ControlPointRule::Spread}, {"cover", ControlPointRule::Cover}}))
      ->default_str("spread");
}

FeatureMap featuresFromOptions(const FeatureOptions& options, const Robot& robot) {
  const FeatureKind kind = parseFeatureKind(options.kind);
  if (kind == FeatureKind::JointScaling) {
    if (!options.controlLinks.empty()) {
      throw InvalidArgument("--control-links needs --features fk");
    }
    return robotFeatures(robot, kind);
  }
  std::vector<ControlPoint> points = options.controlLinks.empty()
                                         ? defaultControlPoints(robot, options.automatic)
                                         : namedControlPoints(robot, options.controlLinks);
  return robotFeatures(robot, kind, std::move(points));
}

}  // namespace fastron::cli
