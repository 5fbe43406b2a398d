#pragma once
// The options that choose a robot: --robot, --joints, --package-path, --srdf.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "fastron/core/feature_map.h"
#include "fastron/geometry/control_points.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene.h"

namespace fastron::cli {

struct RobotOptions {
  std::string robot;
  std::vector<std::string> joints;
  std::vector<std::string> packagePaths;
  std::string srdf;   ///< a MoveIt SRDF whose disabled collisions apply
  std::string group;  ///< an SRDF group whose joints are actuated
};

void addRobotOptions(CLI::App& cmd, RobotOptions& options, bool required = true);

/// The shipped robot or URDF, with --joints or --group applied; prints the SRDF's warnings
/// (entries naming links the URDF lacks, skipped) to stderr.
Robot loadRobotFromOptions(const RobotOptions& options);
/// The same with the SRDF's groups and warnings.
RobotDescription robotDescriptionFromOptions(const RobotOptions& options);

/// The joint values given to `option` (e.g. "--config") as a configuration of `robot`; throws
/// InvalidArgument naming the option, the count and the robot's actuated joints when the count
/// differs.
Eigen::VectorXd configurationFromOption(const std::vector<double>& values, const Robot& robot,
                                        const char* option);

/// The options that choose a model's features: --features, --control-links, --control-points.
struct FeatureOptions {
  std::string kind = "fk";
  std::vector<std::string>
      controlLinks;               ///< LINK or LINK@X:Y:Z per control point (default: automatic)
  ControlPointOptions automatic;  ///< the automatic choice's cap and spacing
};

void addFeatureOptions(CLI::App& cmd, FeatureOptions& options);
/// --features alone (fk or joints), for commands that choose only the kind.
void addFeatureKindOption(CLI::App& cmd, std::string& kind);

/// The features of a model of `robot` chosen by the options.
FeatureMap featuresFromOptions(const FeatureOptions& options, const Robot& robot);

}  // namespace fastron::cli
