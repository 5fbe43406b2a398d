#pragma once
// The paper's cheaper, approximate checker: forward kinematics, then a GJK intersection test
// (libccd, called directly) between every robot shape and every obstacle, with no broad phase.
// Robot links are boxes, spheres, cylinders or capsules; a mesh is replaced by its convex hull
// (the support function of its vertices), as are mesh obstacles. Point clouds are refused
// (Unsupported): a cloud is no convex body, and a GJK run per point is what FclChecker avoids.

#include <memory>
#include <mutex>

#include "fastron/core/export.h"
#include "fastron/geometry/scene_checker.h"
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

/// The scene checker named "gjk" (scene_checkers.h). Measures no distances.
class GjkChecker final : public SceneChecker {
 public:
  GjkChecker(Robot robot, const Scene& scene, CheckerOptions options = {});
  ~GjkChecker() override;

  std::string name() const override { return "GJK"; }
  const Robot& robot() const override { return robot_; }
  const CheckerOptions& options() const override { return options_; }
  /// Safe while other threads check, as FclChecker::setScene.
  void setScene(const Scene& scene) override;

 protected:
  bool check(const double* q) const override;
  std::size_t checkFirst(const double* q, std::size_t n) const override;
  void checkEach(const double* q, std::size_t n, std::uint8_t* out) const override;
  std::optional<Contact> contactAt(const double* q) const override;

 private:
  struct World;
  struct Scratch;
  /// Two shapes that touch: a robot shape and an obstacle, or two robot shapes.
  struct Touch {
    std::size_t shape = 0, other = 0;
    bool self = false;
  };
  /// Places the robot at q in `scratch`; the first touch with an obstacle of `world` or itself.
  std::optional<Touch> firstTouch(const World& world, Scratch& scratch, const double* q) const;
  /// The first obstacle robot shape `shape`, placed as `body`, touches and may not touch.
  std::optional<std::size_t> touchedObstacle(const World& world, const ConvexBody& body,
                                             std::size_t shape) const;

  Robot robot_;
  CheckerOptions options_;
  std::vector<ConvexBody> robotBodies_;   // in their link frames (pose = shape origin)
  std::vector<std::uint8_t> shapeMoves_;  // shapesMovedByConfiguration(robot_)
  Snapshot<World> world_;
  mutable ScratchPool<Scratch> scratch_;
};

}  // namespace fastron
