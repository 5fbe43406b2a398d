#pragma once
// The exact checker of the paper's changing-environment experiments: forward kinematics, then
// FCL 0.7 (libccd GJK solver) between the robot's links and the obstacles, with FCL's dynamic
// AABB tree as broad phase, and optional self-collision. With CheckerOptions::proveMotionsFree (the
// default), in a scene without point clouds and of at most 256 robot shape-obstacle pairs, a
// configuration's check bounds every pair from balls first and asks FCL only about the pairs they
// do not keep apart (certifiedStateCheck): the same answers, as fast or faster (labels of
// generated scenes 1.6-4.3 times: docs/geometry.md). Point clouds are checked beside FCL's
// broad phase: their balls sorted into a grid (cloud_grid.h) once per scene, a link's box picks
// the balls near it, and each is tested exactly (in closed form against a primitive, by FCL
// against a mesh) — the answers of FCL on one sphere per point, in a fraction of the time.

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/certified_motion.h"
#include "fastron/geometry/scene_checker.h"
#include "fastron/geometry/scratch_pool.h"
#include "fastron/geometry/snapshot.h"

namespace fcl {
template <typename S>
class CollisionObject;
}  // namespace fcl

namespace FASTRON_API fastron {

/// The scene checker named "fcl" (scene_checkers.h).
class FclChecker final : public SceneChecker {
 public:
  FclChecker(Robot robot, const Scene& scene, CheckerOptions options = {});
  ~FclChecker() override;

  std::string name() const override { return "FCL"; }
  const Robot& robot() const override { return robot_; }
  const CheckerOptions& options() const override { return options_; }
  /// With options.proveMotionsFree, a motion's check skips the states that clearance bounds
  /// prove free (certified_motion.h) and asks FCL only about the pairs of shapes no bound keeps
  /// apart, for robots of meshes too: planners' edges and verification's (docs/planning.md).
  bool provesMotionsFree() const override { return options_.proveMotionsFree; }
  /// True when a configuration's check in the current scene bounds every pair from balls first
  /// and asks FCL only about the pairs they do not keep apart (certifiedStateCheck): with
  /// options.proveMotionsFree, no point clouds and at most 256 robot shape-obstacle pairs.
  bool boundsStateChecks() const;
  /// Self pairs with a table of their distance (CheckerOptions::selfPairSlack or selfPairTables).
  std::size_t selfPairTableCount() const;
  /// The tables of the robot's self pairs (built, or CheckerOptions::selfPairTables), for other
  /// checkers of this robot and padding; null for none.
  std::shared_ptr<const std::vector<SelfPairTable>> selfPairTables() const;

  /// Takes the obstacles' new poses (and the scene's robot base and allowed pairs). Safe while
  /// other threads check: a check uses the obstacles it started with. A mesh obstacle's bounding
  /// volume hierarchy is built once per mesh (the same TriangleMesh object) and kept while the
  /// scene still has it: moving a scene updates poses only.
  void setScene(const Scene& scene) override;
  /// Mesh obstacle hierarchies built so far (once per distinct mesh the scenes held).
  std::size_t meshHierarchiesBuilt() const { return meshBuilds_; }

  /// Every pair of robot links in contact at q, each pair once (the link that comes first in
  /// robot().links() first). Empty unless the checker was built with options.selfCollision;
  /// obstacles are not looked at.
  std::vector<Contact> selfContacts(std::span<const double> q) const;

  bool measuresDistance() const override { return true; }

 protected:
  bool check(const double* q) const override;
  std::size_t checkFirst(const double* q, std::size_t n) const override;
  void checkEach(const double* q, std::size_t n, std::uint8_t* out) const override;
  MotionCheck checkMotion(const double* from, const double* to,
                          std::size_t segments) const override;
  std::optional<Contact> contactAt(const double* q) const override;
  double distanceAt(const double* q) const override;

 private:
  struct Geometry;
  struct Obstacles;
  struct Scratch;
  struct Cloud;
  /// `cloud` (its points posed by `pose`) cropped to the robot's reach from `robotBase`, in a grid.
  Cloud placeCloud(const PointCloud& cloud, const Eigen::Isometry3d& pose,
                   const Eigen::Isometry3d& robotBase) const;
  /// True when robot shape `shape`, placed as `object`, touches a ball of `cloud`.
  bool touchesCloud(const Cloud& cloud, std::size_t shape,
                    const fcl::CollisionObject<double>& object) const;
  /// The first cloud of `world` that shape `shape`, placed as `object`, may not touch but does.
  const Cloud* touchedCloud(const Obstacles& world, std::size_t shape,
                            const fcl::CollisionObject<double>& object) const;
  /// The distance from robot shape `shape`, placed as `object`, to the nearest ball of `cloud`.
  double cloudDistance(const Cloud& cloud, std::size_t shape,
                       const fcl::CollisionObject<double>& object) const;
  void placeRobot(Scratch& scratch, const Eigen::Isometry3d& base, const double* q) const;
  /// The shapes no configuration moves, placed in `world`, and their contacts (Obstacles).
  void placeFixedShapes(Obstacles& world) const;
  /// How fast the distance of robot shapes a and b can shrink per unit of each coordinate: the
  /// levers of the joints between their links and the link they both hang from.
  Eigen::VectorXd selfPairLevers(const Geometry& geometry, std::size_t a, std::size_t b) const;
  /// The tables of CheckerOptions::selfPairSlack for the robot's self pairs of meshes that one or
  /// two coordinates turn against each other, from `geometry`'s distance shapes and covers; the
  /// pairs built on every core.
  std::shared_ptr<const std::vector<SelfPairTable>> tabulateSelfPairs(
      const Geometry& geometry) const;
  /// The pairs that must not touch in `world`, with the bounds that prove them apart.
  void buildClearance(Obstacles& world, const Scene& scene) const;
  /// True when the levers hold along the motion: every prismatic coordinate within its limits.
  bool leversHold(const double* from, const double* to) const;
  /// The clearance certificate's questions to FCL on `scratch`'s placement, about the world
  /// `scratch` was last aimed at (made once per scratch).
  ExactPairCheck exactPairCheck(Scratch& scratch) const;
  /// `scratch`'s questions, aimed at `world`.
  const ExactPairCheck& exactPairs(const Obstacles& world, Scratch& scratch) const;
  /// True when q collides with `world` or the robot itself: the clearance certificate's check
  /// (certifiedStateCheck) where it holds, else collide.
  bool collides(const Obstacles& world, Scratch& scratch, const double* q) const;
  /// Places the robot at q in `scratch`, then the first contact with `world` or itself.
  std::optional<Contact> collide(const Obstacles& world, Scratch& scratch, const double* q,
                                 bool wantContact) const;

  Robot robot_;
  CheckerOptions options_;
  std::shared_ptr<const Geometry> geometry_;  // robot shapes as FCL geometry
  Snapshot<Obstacles> obstacles_;
  std::atomic<std::size_t> meshBuilds_{0};
  // FCL's CollisionObject constructor writes its geometry's local box: objects of the robot's
  // shared geometries (a thread's scratch, a scene's fixed shapes) are made under this lock.
  mutable std::mutex objectsOfRobotGeometry_;
  mutable ScratchPool<Scratch> scratch_;
};

}  // namespace fastron
