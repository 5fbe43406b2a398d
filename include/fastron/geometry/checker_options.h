#pragma once
// What the robot-against-scene checkers (FclChecker, GjkChecker) share: their options, padded
// robot shapes, and the robot-obstacle pairs a scene allows to touch.

#include <cstdint>
#include <memory>
#include <vector>

#include "fastron/core/collision_checker.h"
#include "fastron/core/export.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/scene.h"
#include "fastron/geometry/self_pair_table.h"

namespace FASTRON_API fastron {

/// Options of the robot-against-scene checkers (FclChecker, GjkChecker).
struct CheckerOptions {
  bool selfCollision = false;  ///< also check link pairs not allowed to touch
  double padding = 0;          ///< grow every robot shape by this much (not meshes)
  /// Check whole motions with clearance bounds, skipping the states they prove free
  /// (certified_motion.h; FclChecker): the same answers as a check of every state.
  bool proveMotionsFree = true;
  /// With selfCollision and proveMotionsFree (FclChecker): each self pair that holds a mesh and
  /// that one or two joint coordinates alone turn against each other gets a table of the two
  /// shapes' exact distance over those coordinates (self_pair_table.h), with nodes close enough
  /// that the levers take at most this much (metres) off a node's distance; the certificate
  /// reads its bound before the balls'. 0: no tables. Building one costs an FCL mesh distance per
  /// node (55-400 µs each on the mesh Panda), so this is for checkers that check many states.
  double selfPairSlack = 0;
  /// With selfCollision and proveMotionsFree (FclChecker): tables built before for this robot and
  /// padding (FclChecker::selfPairTables of another checker, or pipeline::selfPairTables, which
  /// keeps them in a cache), used instead of building any (selfPairSlack is then not used). Null:
  /// build them when selfPairSlack says so. The checker refuses tables that do not fit the robot
  /// (checkSelfPairTable); it cannot tell tables of another robot of the same sizes.
  std::shared_ptr<const std::vector<SelfPairTable>> selfPairTables = nullptr;
};

/// Robot shape `index` grown by options.padding; throws InvalidArgument naming the link when it
/// cannot be padded (a mesh) or the padding is invalid.
Shape paddedShape(const Robot& robot, std::size_t index, const CheckerOptions& options);

/// Robot-obstacle pairs the scene allows to touch (its allowed collision matrix names a link and an
/// obstacle, e.g. a grasped object and the hand): allowed[s * obstacles + o] = 1 when robot shape s
/// may touch obstacle o. Empty when the scene allows no such pair.
std::vector<std::uint8_t> allowedObstacleContacts(const Robot& robot, const Scene& scene);

}  // namespace fastron
