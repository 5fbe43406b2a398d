#pragma once
// The robots shipped in data/robots (catalogue: data/robots/robots.yaml).

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/srdf.h"
#include "fastron/geometry/urdf.h"

namespace FASTRON_API fastron {

struct RobotEntry {
  std::string name, description;
  std::filesystem::path urdf;
  std::vector<std::string> joints;                   ///< actuated, in order
  std::vector<std::pair<std::string, double>> held;  ///< positions of other joints
  std::vector<std::pair<std::string, std::string>> allowedCollisions;  ///< links touching by design
  std::filesystem::path srdf;  ///< MoveIt SRDF whose disabled collisions apply (empty: none)
};

/// The data folder (robots/, scenes/): $FASTRON_DATA_DIR if set, else the installation's
/// share/fastron (installedShareDirectory). Throws FileError when there is neither.
std::filesystem::path dataDirectory();

/// Every shipped robot, from data/robots/robots.yaml.
std::vector<RobotEntry> shippedRobots();

/// A robot catalogue from a string (the format of data/robots/robots.yaml); its urdf and srdf
/// paths are taken relative to `directory`. Throws FileError naming `source` and the line.
std::vector<RobotEntry> parseRobotCatalogue(const std::string& yaml, const std::string& source,
                                            const std::filesystem::path& directory);

/// A robot with what its SRDFs say of it.
struct RobotDescription {
  Robot robot;  ///< the SRDFs' disabled collisions among its allowed ones
  /// The catalogue's SRDF and then the given one, merged: a later group replaces one of the same
  /// name; the warnings of both (entries naming links the URDF lacks, skipped).
  Srdf srdf;
  /// What was read and set aside, for the caller to show: the URDF's floating and planar joints
  /// (held at their origin), then srdf.warnings.
  std::vector<std::string> warnings;
};

/// A shipped robot by name (its catalogue joints actuated, its allowed pairs and SRDF applied;
/// package:// meshes found beside its URDF), or else a URDF file (every movable joint actuated).
/// A non-empty `srdf` adds that file's disabled collisions and groups (loadSrdf). Throws
/// FileError when it is neither, naming the shipped robots.
RobotDescription loadRobotDescription(const std::string& nameOrPath,
                                      const UrdfOptions& options = {},
                                      const std::filesystem::path& srdf = {});

/// loadRobotDescription's robot, for callers that need neither the groups nor the warnings.
Robot loadRobot(const std::string& nameOrPath, const UrdfOptions& options = {},
                const std::filesystem::path& srdf = {});

}  // namespace fastron
