#pragma once
// The paper's cheaper, approximate checker: forward kinematics, then a GJK intersection test
// (libccd, called directly) between every robot shape and every obstacle, with no broad phase.
// Robot links are boxes, spheres, cylinders or capsules; a mesh is replaced by its convex hull
// (the support function of its vertices), as are mesh obstacles.

#include <memory>
#include <mutex>

#include "fastron/core/export.h"
#include "fastron/geometry/checker_options.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/scene.h"
#include "fastron/geometry/scratch_pool.h"
#include "fastron/geometry/snapshot.h"

namespace FASTRON_API fastron {

/// A convex shape placed in the world, with the support function GJK needs.
struct ConvexBody {
  enum class Kind { Box, Sphere, Cylinder, Capsule, Hull } kind = Kind::Sphere;
  Eigen::Vector3d halfSize = Eigen::Vector3d::Zero();        ///< box
  double radius = 0, halfLength = 0;                         ///< sphere, cylinder, capsule
  std::shared_ptr<const std::vector<Eigen::Vector3d>> hull;  ///< mesh vertices
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();

  static ConvexBody from(const Shape& shape);
  /// The point of the body farthest along `direction` (world frame).
  Eigen::Vector3d support(const Eigen::Vector3d& direction) const;
};

/// True when the two bodies intersect (libccd's GJK).
bool gjkIntersect(const ConvexBody& a, const ConvexBody& b);

class GjkChecker final : public CollisionChecker {
 public:
  GjkChecker(Robot robot, const Scene& scene, CheckerOptions options = {});
  ~GjkChecker() override;

  std::string name() const override { return "GJK"; }
  std::size_t dof() const override { return robot_.dof(); }
  const Robot& robot() const { return robot_; }
  /// Safe while other threads check, as FclChecker::setScene.
  void setScene(const Scene& scene);

 protected:
  bool check(const double* q) const override;
  std::size_t checkFirst(const double* q, std::size_t n) const override;
  void checkEach(const double* q, std::size_t n, std::uint8_t* out) const override;

 private:
  struct World;
  struct Scratch;
  /// Places the robot at q in `scratch`; true when it touches an obstacle of `world` or itself.
  bool collides(const World& world, Scratch& scratch, const double* q) const;
  /// Whether robot shape `shape`, placed as `body`, touches an obstacle it may not touch.
  bool obstacleTouches(const World& world, const ConvexBody& body, std::size_t shape) const;

  Robot robot_;
  CheckerOptions options_;
  std::vector<ConvexBody> robotBodies_;   // in their link frames (pose = shape origin)
  std::vector<std::uint8_t> shapeMoves_;  // shapesMovedByConfiguration(robot_)
  Snapshot<World> world_;
  mutable ScratchPool<Scratch> scratch_;
};

}  // namespace fastron
