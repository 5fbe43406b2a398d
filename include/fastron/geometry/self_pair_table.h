#pragma once
// A lower bound on the distance of two robot shapes that one or two joint coordinates alone turn
// against each other (the mesh Panda's link 5 against link 7 and the hand: joints 6 and 7): their
// exact distance tabulated at the nodes of a grid over those coordinates, less the most that the
// levers let it fall between the nearest node and the configuration asked about. A bound, never
// an estimate, and a lookup instead of an FCL check of two meshes that sit a centimetre apart
// (docs/geometry.md, "Whole motions, and what clearance proves").

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/joint_limits.h"

namespace FASTRON_API fastron {

/// Immutable once built: read from any number of threads.
struct SelfPairTable {
  std::size_t shapeA = 0, shapeB = 0;        ///< robot shapes (Robot::shapes() indices)
  std::size_t axes = 0;                      ///< the coordinates tabulated: 1 or 2
  std::array<std::size_t, 2> coordinate{};   ///< their indices in a configuration
  std::array<double, 2> lower{}, spacing{};  ///< each axis's first node and node spacing
  std::array<double, 2> lever{};             ///< how fast the distance can shrink along each
  std::array<std::size_t, 2> nodes{1, 1};    ///< nodes along each axis
  std::vector<float> distance;  ///< per node, the first axis fastest; rounded down to float

  /// A lower bound on the shapes' distance at configuration q: the nearest node's distance less
  /// sum lever |q - node| over the axes. -infinity for a non-finite coordinate.
  double lowerBound(const double* q) const;
};

/// Throws InvalidArgument, naming `source` and the field, unless `table` is whole and fits a robot
/// of `shapes` collision shapes and `dof` configuration coordinates: two distinct shapes, 1 or 2
/// axes on distinct coordinates, finite node positions, spacings > 0, levers >= 0, nodes >= 1 and
/// one distance per node. It cannot tell whether the distances are the robot's: a table is only
/// as good as the robot and padding it was built for (pipeline::selfPairTables keys its cache so).
void checkSelfPairTable(const SelfPairTable& table, std::size_t shapes, std::size_t dof,
                        const std::string& source);

/// The table of shapes a and b over the coordinates where `levers` (how fast their distance can
/// shrink per unit of each configuration coordinate: ClearancePair::levers) is not zero, within
/// `limits`, with nodes close enough that the levers take at most `slack` off a node's distance
/// (lever x half the spacing, summed over the axes). `distance(q)` is the shapes' exact distance
/// at configuration q (limits.dim() values); the coordinates outside the table must not move one
/// shape against the other, which zero levers say. std::nullopt when no coordinate or more than
/// two have a lever, when a tabulated coordinate's range is not finite, or when the grid would
/// need more than `maxNodes`. Throws InvalidArgument unless slack is finite and positive and
/// levers has limits.dim() finite values >= 0.
std::optional<SelfPairTable> tabulateSelfPair(std::size_t a, std::size_t b,
                                              const Eigen::VectorXd& levers,
                                              const JointLimits& limits, double slack,
                                              std::size_t maxNodes,
                                              const std::function<double(const double*)>& distance);

}  // namespace fastron
