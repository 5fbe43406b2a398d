#pragma once
// Straight-line motions in joint space, paths of waypoints, and the exact check of a whole path:
// the one discretisation every planner, verifier and test of Fastron shares.

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/collision_checker.h"
#include "fastron/core/export.h"
#include "fastron/core/motion_states.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

/// A path of joint-space waypoints, joined by straight lines.
using JointPath = std::vector<Eigen::VectorXd>;

/// segmentCount (core/motion_states.h) of two configurations; throws InvalidArgument when their
/// sizes differ.
std::size_t segmentCount(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double resolution);

/// Sum of the Euclidean lengths of the path's edges.
double pathLength(const JointPath& path);

/// Writes `path` as CSV: a header of the joint names, then one waypoint per row at full
/// precision (atomically, as every file Fastron writes). Throws InvalidArgument when a waypoint
/// has another length than the names, FileError when the file cannot be written.
void writePathCsv(const JointPath& path, const std::vector<std::string>& jointNames,
                  const std::filesystem::path& file);

/// Reads a path as writePathCsv writes it: a header of joint names, then one waypoint per row.
/// The header must name `jointNames` in that order; a file without a header must have one
/// column per joint. Throws FileError naming the file, and the line and column, of the first
/// problem: a header naming other joints, a ragged row, a value that is not a finite number, no
/// waypoint.
JointPath readPathCsv(const std::filesystem::path& file,
                      const std::vector<std::string>& jointNames);
/// The same reader on the text of a file; errors name `source` as they would the file.
JointPath parsePathCsv(std::string_view text, const std::string& source,
                       const std::vector<std::string>& jointNames);

/// segmentCount of every edge of `path` at `resolution` (edge e joins waypoints e and e + 1): the
/// states statesAlongPath puts on each edge, its first waypoint included.
std::vector<std::size_t> edgeSegments(const JointPath& path, double resolution);

/// Every state a check of `path` at `resolution` looks at, in the path's order: each waypoint,
/// then the interior states of the edge that leaves it (segmentCount segments, as checkPath
/// cuts them), and the last waypoint. One row per state.
Configurations statesAlongPath(const JointPath& path, double resolution);

/// What the exact checker says about a path.
struct PathCheck {
  std::vector<std::size_t> invalidWaypoints;  ///< waypoints in collision
  std::vector<std::size_t> invalidEdges;      ///< edge i joins waypoints i and i + 1
  bool valid() const { return invalidWaypoints.empty() && invalidEdges.empty(); }
};

/// Throws InvalidArgument naming the first waypoint that does not hold `dim` values.
void checkWaypointSizes(const JointPath& path, std::size_t dim);

/// Checks every waypoint, and every edge at `resolution`, with `checker`. An empty path is
/// invalid (waypoint 0 is reported). Throws InvalidArgument on waypoints of the wrong dimension.
PathCheck checkPath(const CollisionChecker& checker, const JointPath& path, double resolution);

}  // namespace fastron
