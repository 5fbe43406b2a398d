#include "fastron/planning/motion.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <string>

#include "fastron/core/csv_table.h"
#include "fastron/core/error.h"
#include "fastron/core/file_io.h"

namespace fastron {

std::size_t segmentCount(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double resolution) {
  if (a.size() != b.size()) {
    throw InvalidArgument("motion between configurations of " + std::to_string(a.size()) + " and " +
                          std::to_string(b.size()) + " values");
  }
  return segmentCount(a.data(), b.data(), static_cast<std::size_t>(a.size()), resolution);
}

double pathLength(const JointPath& path) {
  double length = 0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

void checkWaypointSizes(const JointPath& path, std::size_t dim) {
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (static_cast<std::size_t>(path[i].size()) != dim) {
      throw InvalidArgument("path waypoint " + std::to_string(i) + " has " +
                            std::to_string(path[i].size()) + " values, the checker expects " +
                            std::to_string(dim));
    }
  }
}

PathCheck checkPath(const CollisionChecker& checker, const JointPath& path, double resolution) {
  PathCheck check;
  if (path.empty()) {
    check.invalidWaypoints.push_back(0);
    return check;
  }
  const std::size_t dim = checker.dof();
  checkWaypointSizes(path, dim);
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (checker.inCollision(std::span<const double>(path[i].data(), dim))) {
      check.invalidWaypoints.push_back(i);
    }
  }
  std::vector<double> states;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const std::size_t n = segmentCount(path[i], path[i + 1], resolution);
    motionStates(path[i].data(), path[i + 1].data(), dim, n, states);
    // The end state is waypoint i + 1, already checked: the interior states are rows 1..n-1.
    for (std::size_t r = 1; r < n; ++r) {
      if (checker.inCollision(std::span<const double>(states.data() + r * dim, dim))) {
        check.invalidEdges.push_back(i);
        break;
      }
    }
  }
  return check;
}

void writePathCsv(const JointPath& path, const std::vector<std::string>& jointNames,
                  const std::filesystem::path& file) {
  std::ostringstream out;
  for (std::size_t j = 0; j < jointNames.size(); ++j) out << (j ? "," : "") << jointNames[j];
  out << '\n' << std::setprecision(17);
  for (const Eigen::VectorXd& q : path) {
    if (static_cast<std::size_t>(q.size()) != jointNames.size()) {
      throw InvalidArgument("writePathCsv: a waypoint of " + std::to_string(q.size()) +
                            " values for " + std::to_string(jointNames.size()) + " joints");
    }
    for (Eigen::Index j = 0; j < q.size(); ++j) out << (j ? "," : "") << q[j];
    out << '\n';
  }
  writeFileAtomically(file, out.view(), "path file");
}

JointPath readPathCsv(const std::filesystem::path& file,
                      const std::vector<std::string>& jointNames) {
  return parsePathCsv(readFile(file, "path file"), file.string(), jointNames);
}

JointPath parsePathCsv(std::string_view text, const std::string& source,
                       const std::vector<std::string>& jointNames) {
  const CsvTable table = parseCsvTable(text, source);
  if (table.firstLine == 0) throw FileError(source + ": no waypoints");
  const std::string where = source + ":" + std::to_string(table.firstLine);
  if (!table.header.empty()) {
    for (std::size_t c = 0; c < std::max(table.columns, jointNames.size()); ++c) {
      const std::string named = c < table.columns ? table.header[c] : "nothing";
      const std::string joint = c < jointNames.size() ? jointNames[c] : "no joint";
      if (named != joint) {
        throw FileError(where + ": column " + std::to_string(c + 1) + " is '" + named +
                        "', but the robot's joint " + std::to_string(c + 1) + " is '" + joint +
                        "' (a path file's header names the robot's joints in order)");
      }
    }
  } else if (table.columns != jointNames.size()) {
    throw FileError(where + ": " + std::to_string(table.columns) + " columns, but the robot has " +
                    std::to_string(jointNames.size()) + " joints");
  }
  if (table.rows() == 0) throw FileError(source + ": no waypoints");
  JointPath path;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    path.emplace_back(Eigen::Map<const Eigen::VectorXd>(table.values.data() + i * table.columns,
                                                        static_cast<Eigen::Index>(table.columns)));
  }
  return path;
}

std::vector<std::size_t> edgeSegments(const JointPath& path, double resolution) {
  std::vector<std::size_t> segments;
  for (std::size_t e = 0; e + 1 < path.size(); ++e)
    segments.push_back(segmentCount(path[e], path[e + 1], resolution));
  return segments;
}

Configurations statesAlongPath(const JointPath& path, double resolution) {
  if (path.empty()) return {};
  const auto dim = path.front().size();
  checkWaypointSizes(path, static_cast<std::size_t>(dim));
  const std::vector<std::size_t> segments = edgeSegments(path, resolution);
  const std::size_t count = 1 + std::accumulate(segments.begin(), segments.end(), std::size_t{0});
  Configurations states(static_cast<Eigen::Index>(count), dim);
  Eigen::Index row = 0;
  for (std::size_t e = 0; e < segments.size(); ++e) {
    for (std::size_t i = 0; i < segments[e]; ++i) {
      const double t = static_cast<double>(i) / static_cast<double>(segments[e]);
      for (Eigen::Index j = 0; j < dim; ++j) {  // as motionStates computes them
        states(row, j) = path[e][j] + t * (path[e + 1][j] - path[e][j]);
      }
      ++row;
    }
  }
  states.row(row) = path.back().transpose();
  return states;
}

}  // namespace fastron
