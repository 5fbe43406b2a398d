#pragma once
// The seam of the exact checkers: a robot checked against a scene (obstacles, the robot's base,
// the pairs allowed to touch). FclChecker and GjkChecker implement it; makeSceneChecker
// (scene_checkers.h) builds one by name, which is how the commands, the pipeline and Python choose
// their oracle. A new backend implements this interface and adds one line to that factory.

#include <optional>
#include <span>
#include <string>

#include "fastron/core/collision_checker.h"
#include "fastron/core/export.h"
#include "fastron/geometry/checker_options.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/scene.h"

namespace FASTRON_API fastron {

/// What collided: a robot link and an obstacle, or two robot links (self-collision).
struct Contact {
  std::string robotLink;
  std::string other;
  bool selfCollision = false;
};

/// "right_hand touches box", or "panda_link7 touches link panda_link5" for a self-collision.
std::string describe(const Contact& contact);

/// A robot against a scene, exactly. As every CollisionChecker, safe to call from many threads at
/// once; setScene is safe while other threads check (a check uses the scene it started with).
class SceneChecker : public CollisionChecker {
 public:
  /// The robot checked (its joints are the configuration's).
  virtual const Robot& robot() const = 0;
  /// The options it was built with.
  virtual const CheckerOptions& options() const = 0;
  std::size_t dof() const final { return robot().dof(); }

  /// Takes the scene's obstacles, robot base and allowed pairs, for the checks that start after.
  virtual void setScene(const Scene& scene) = 0;

  /// The first contact found at q, or nothing when q is free. Throws InvalidArgument on a wrong
  /// length or a non-finite value.
  std::optional<Contact> firstContact(std::span<const double> q) const;

  /// True when distance() answers (FCL); false when the backend only tells contact (GJK: libccd
  /// 2.1 has no distance query).
  virtual bool measuresDistance() const { return false; }
  /// Smallest distance between the robot and any obstacle (self-collision not measured); 0 when
  /// in collision. Throws InvalidArgument on a wrong length or a non-finite value, Unsupported
  /// when measuresDistance() is false.
  double distance(std::span<const double> q) const;

 protected:
  /// firstContact for dof() finite values.
  virtual std::optional<Contact> contactAt(const double* q) const = 0;
  /// distance for dof() finite values; by default throws Unsupported naming the checker.
  virtual double distanceAt(const double* q) const;
};

}  // namespace fastron
