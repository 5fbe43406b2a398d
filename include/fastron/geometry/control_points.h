#pragma once
// Control points on a robot's links, where task-space features are measured: chosen automatically
// (defaultControlPoints) or named by the user.

#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {

/// How defaultControlPoints orders the candidates it takes.
enum class ControlPointRule {
  /// By how much they move, the points far down the chain first (measured on Baxter and the
  /// Panda: docs/algorithms.md).
  Spread,
  /// A greedy cover of the moving geometry: the point that moves most, then each time the one
  /// least explained by the points taken (its mean distance to the nearest of them, capped by how
  /// much it moves at all), so that the points spread along the chain (a hand, then an elbow, an
  /// upper arm) rather than crowd the hand. Measured on robots the spread rule was not tuned on:
  /// docs/algorithms.md, "Control points on robots of other makers".
  Cover,
};

/// How control points are chosen automatically (see defaultControlPoints).
struct ControlPointOptions {
  ControlPointRule rule = ControlPointRule::Spread;
  /// At most this many points (0 = every candidate left after the spacing rule). More points
  /// cost query time and, measured on Baxter and the Panda, do not buy accuracy (the points far
  /// down the chain are the ones that collide): docs/algorithms.md.
  std::size_t maxPoints = 4;
  /// A candidate closer than this (mean distance over sampled configurations, metres) to a point
  /// already chosen adds little and is skipped.
  double minSpacing = 0.1;
  /// At most this many points on one rigid body (links joined by fixed or held joints; 0 = no
  /// limit): three fix the body's pose, so a fourth adds nothing a kernel over positions can use,
  /// and without the limit the mesh Panda's large hand took every point and left the forearm
  /// unseen.
  std::size_t maxPerBody = 3;
  /// Also candidates along every link's collision geometry: the centre of its bounding box and
  /// the centres of the two faces at the ends of its longest side. For a kernel of point terms
  /// alone (answered by a point field, where a point costs one grid read) that must see a long
  /// link anywhere along it: the mesh Panda's box scene went from TPR 0.884 with the default
  /// candidates to 0.966 with points along its forearm (docs/performance.md).
  bool alongGeometry = false;

  bool operator==(const ControlPointOptions&) const = default;
};

/// The control points a task-space model of `robot` uses by default. Candidates are the origins
/// of the links that move under the actuated joints, and, for each link with collision geometry
/// but no moving descendant, the far end of its geometry (the centre of the face of its bounding
/// box farthest from the link origin along the longest side). The candidates are placed at 64
/// seeded random configurations; a candidate that stays within 1 mm of one place is dropped.
/// The rest are taken in the order of options.rule (Spread: how much they move, the standard
/// deviation of the position; Cover: see ControlPointRule), skipping one closer than
/// options.minSpacing on average to a point already taken or on a rigid body that has
/// options.maxPerBody points already, up to options.maxPoints. The result depends only on the
/// robot and the options.
std::vector<ControlPoint> defaultControlPoints(const Robot& robot,
                                               const ControlPointOptions& options = {});

/// Control points named by the user, in order: "LINK" is the link's origin, "LINK@X:Y:Z" the
/// point at offset (X, Y, Z) metres in the link's frame. Throws InvalidArgument naming an unknown
/// link or a malformed offset.
std::vector<ControlPoint> namedControlPoints(const Robot& robot,
                                             const std::vector<std::string>& specs);

}  // namespace fastron
