#pragma once
// Robots from URDF files, read with urdfdom.

#include <filesystem>
#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {

struct UrdfOptions {
  /// Where `package://name/...` and relative mesh paths are looked up: for package URIs, a
  /// folder that contains `name/` or is itself named `name`. Relative paths are tried next to the
  /// URDF file first; package URIs, after these folders, as ROS finds packages: the URDF's folder
  /// and its ancestors, then the folders of ROS_PACKAGE_PATH and the `share/` of those of
  /// AMENT_PREFIX_PATH.
  std::vector<std::filesystem::path> searchPaths;
  /// Turn a cylinder with a sphere of its radius on each end (in one link) into one capsule.
  bool mergeCapsules = true;
};

/// Reads a URDF: revolute, continuous, prismatic and fixed joints, floating and planar joints
/// (fixed at their origin, Joint::heldMultiDof), limits, mimic joints (which follow their joint
/// and are never actuated), and collision geometry (box, cylinder, sphere, mesh). Throws
/// FileError naming the file, and the line and element where it can: malformed XML, unknown
/// geometry (urdfdom would silently drop it), zero or negative sizes, non-finite numbers, lower
/// limit above upper, unknown joint types, missing meshes.
Robot loadUrdf(const std::filesystem::path& file, const UrdfOptions& options = {});

/// The same from a string; `source` names it in messages and relative paths start from
/// `baseDirectory`.
Robot parseUrdf(const std::string& xml, const std::string& source, const UrdfOptions& options = {},
                const std::filesystem::path& baseDirectory = {});

}  // namespace fastron
