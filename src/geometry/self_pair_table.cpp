#include "fastron/geometry/self_pair_table.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "fastron/core/error.h"

namespace fastron {

double SelfPairTable::lowerBound(const double* q) const {
  std::size_t index = 0, stride = 1;
  double fall = 0;
  for (std::size_t k = 0; k < axes; ++k) {
    const double value = q[coordinate[k]];
    if (!std::isfinite(value)) return -std::numeric_limits<double>::infinity();
    const double last = static_cast<double>(nodes[k] - 1);
    const double nearest = std::clamp(std::round((value - lower[k]) / spacing[k]), 0.0, last);
    fall += lever[k] * std::abs(value - (lower[k] + nearest * spacing[k]));
    index += static_cast<std::size_t>(nearest) * stride;
    stride *= nodes[k];
  }
  return static_cast<double>(distance[index]) - fall;
}

void checkSelfPairTable(const SelfPairTable& table, std::size_t shapes, std::size_t dof,
                        const std::string& source) {
  const auto fail = [&](const std::string& what) {
    throw InvalidArgument(source + ": self-pair table of shapes " + std::to_string(table.shapeA) +
                          " and " + std::to_string(table.shapeB) + ": " + what);
  };
  if (table.shapeA >= shapes || table.shapeB >= shapes || table.shapeA == table.shapeB)
    fail("needs two distinct shapes of the robot's " + std::to_string(shapes));
  if (table.axes < 1 || table.axes > 2)
    fail("axes must be 1 or 2, not " + std::to_string(table.axes));
  std::size_t count = 1;
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string axis = "axis " + std::to_string(k) + "'s ";
    if (k >= table.axes) {
      if (table.nodes[k] != 1) fail(axis + "nodes must be 1 beyond the table's axes");
      continue;
    }
    if (table.coordinate[k] >= dof)
      fail(axis + "coordinate " + std::to_string(table.coordinate[k]) + " is not below " +
           std::to_string(dof));
    if (!std::isfinite(table.lower[k])) fail(axis + "first node is not finite");
    if (!(std::isfinite(table.spacing[k]) && table.spacing[k] > 0))
      fail(axis + "spacing must be finite and > 0");
    if (!(std::isfinite(table.lever[k]) && table.lever[k] >= 0))
      fail(axis + "lever must be finite and >= 0");
    if (table.nodes[k] < 1 || table.nodes[k] > (std::size_t{1} << 31))
      fail(axis + "node count " + std::to_string(table.nodes[k]) + " is out of range");
    count *= table.nodes[k];
  }
  if (table.axes == 2 && table.coordinate[0] == table.coordinate[1])
    fail("its two axes are one coordinate");
  if (table.distance.size() != count)
    fail(std::to_string(table.distance.size()) + " distances for " + std::to_string(count) +
         " nodes");
}

std::optional<SelfPairTable> tabulateSelfPair(
    std::size_t a, std::size_t b, const Eigen::VectorXd& levers, const JointLimits& limits,
    double slack, std::size_t maxNodes, const std::function<double(const double*)>& distance) {
  if (!(std::isfinite(slack) && slack > 0)) {
    throw InvalidArgument("self-pair table: slack must be finite and > 0, not " +
                          std::to_string(slack));
  }
  if (static_cast<std::size_t>(levers.size()) != limits.dim() || !levers.allFinite() ||
      (levers.array() < 0).any()) {
    throw InvalidArgument("self-pair table: levers need " + std::to_string(limits.dim()) +
                          " finite values >= 0");
  }
  SelfPairTable table;
  table.shapeA = a;
  table.shapeB = b;
  for (Eigen::Index c = 0; c < levers.size(); ++c) {
    if (levers[c] == 0) continue;
    if (table.axes == 2) return std::nullopt;
    table.coordinate[table.axes++] = static_cast<std::size_t>(c);
  }
  if (table.axes == 0) return std::nullopt;
  double count = 1;
  for (std::size_t k = 0; k < table.axes; ++k) {
    const auto c = static_cast<Eigen::Index>(table.coordinate[k]);
    const double range = limits.upper()[c] - limits.lower()[c];
    if (!std::isfinite(range)) return std::nullopt;
    table.lever[k] = levers[c];
    table.lower[k] = limits.lower()[c];
    if (range <= 0) {  // a coordinate that cannot move: its one node
      table.spacing[k] = 1;
      continue;
    }
    // Half a spacing from the nearest node at most, so each axis takes lever x spacing / 2.
    const double widest = 2 * slack / (static_cast<double>(table.axes) * table.lever[k]);
    const double nodes = std::ceil(range / widest) + 1;
    count *= nodes;
    if (count > static_cast<double>(maxNodes)) return std::nullopt;
    table.nodes[k] = static_cast<std::size_t>(nodes);
    table.spacing[k] = range / (nodes - 1);
  }
  table.distance.resize(table.nodes[0] * table.nodes[1]);
  Eigen::VectorXd q = (limits.lower() + limits.upper()) / 2;
  for (std::size_t i = 0; i < table.distance.size(); ++i) {
    const std::size_t at[2] = {i % table.nodes[0], i / table.nodes[0]};
    for (std::size_t k = 0; k < table.axes; ++k) {
      q[static_cast<Eigen::Index>(table.coordinate[k])] =
          table.lower[k] + static_cast<double>(at[k]) * table.spacing[k];
    }
    const double d = distance(q.data());
    // Rounded down, so that the float is a bound too.
    auto stored = static_cast<float>(d);
    if (static_cast<double>(stored) > d) {
      stored = std::nextafter(stored, -std::numeric_limits<float>::infinity());
    }
    table.distance[i] = stored;
  }
  return table;
}

}  // namespace fastron
