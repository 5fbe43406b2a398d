#pragma once
// A robot description: a kinematic tree of links and joints with collision geometry, and the
// choice of actuated joints that make up a configuration (the others are held at fixed values).
// Descriptions are values; per-call scratch lives in KinematicsData (kinematics.h).

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/joint_limits.h"
#include "fastron/geometry/allowed_collisions.h"
#include "fastron/geometry/shapes.h"

namespace FASTRON_API fastron {

enum class JointType { Revolute, Continuous, Prismatic, Fixed };

/// A joint that follows another (URDF's <mimic>): its position is multiplier * the other's +
/// offset.
struct Mimic {
  std::string joint;  ///< the followed joint; after Robot's constructor, one that mimics none
  double multiplier = 1, offset = 0;
};

struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  int parent = -1, child = -1;                               ///< link indices
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< child frame in the parent's
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();           ///< unit, in the child frame
  double lower = 0, upper = 0;  ///< position limits; a continuous joint gets [-pi, pi]
  std::optional<Mimic> mimic;   ///< set when the joint follows another: never actuated
  /// "floating" or "planar" for a URDF joint of several coordinates, read as fixed at its origin:
  /// Fastron plans no such joint, and an arm's planning group leaves it (a mobile base's) where
  /// the robot state puts it, by default its origin. Empty for every other joint.
  std::string heldMultiDof;

  bool movable() const { return type != JointType::Fixed; }
};

struct Link {
  std::string name;
  int parentJoint = -1;  ///< -1 for the root link
};

/// One collision shape attached to a link.
struct LinkShape {
  int link = -1;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< in the link frame
  Shape shape;
};

/// A mimic joint resolved: joints()[joint] is at multiplier * joints()[source] + offset.
struct MimicJoint {
  int joint = -1, source = -1;
  double multiplier = 1, offset = 0;
};

class Robot {
 public:
  /// Checks the tree (unique names, one root, valid indices, no cycles) and orders the joints
  /// parent before child. A mimic of a mimic is resolved to the joint at the end of the chain;
  /// a fixed joint's mimic is dropped (it has nothing to follow with, and MoveIt ignores it).
  /// Every movable joint that mimics none is actuated, in tree order, until setActuatedJoints
  /// says otherwise. Throws InvalidArgument naming the fault (a mimic of an unknown or fixed
  /// joint, or a cycle of mimics among them).
  Robot(std::string name, std::vector<Link> links, std::vector<Joint> joints,
        std::vector<LinkShape> shapes);

  const std::string& name() const { return name_; }
  const std::vector<Link>& links() const { return links_; }
  /// Parent before child: forward kinematics walks them in this order.
  const std::vector<Joint>& joints() const { return joints_; }
  const std::vector<LinkShape>& shapes() const { return shapes_; }
  /// The name of the link that collision shape `shape` belongs to.
  const std::string& shapeLinkName(std::size_t shape) const {
    return links_[static_cast<std::size_t>(shapes_[shape].link)].name;
  }
  int rootLink() const { return root_; }

  /// Index of the link or joint with this name; throws InvalidArgument naming it.
  int linkIndex(std::string_view name) const;
  int jointIndex(std::string_view name) const;

  /// The configuration's coordinates: indices into joints(), in configuration order.
  const std::vector<int>& actuatedJoints() const { return actuated_; }
  std::size_t dof() const { return actuated_.size(); }
  std::vector<std::string> actuatedJointNames() const;
  /// Movable joints that mimic none: those a configuration or a held position may set.
  std::vector<std::string> movableJointNames() const;
  /// Makes these movable joints, in this order, the configuration. Throws InvalidArgument for an
  /// unknown, fixed, mimic or repeated joint, or an empty list.
  void setActuatedJoints(const std::vector<std::string>& names);
  /// The value a joint that is not actuated keeps (default: 0, or the nearest limit); its mimics
  /// follow. Throws InvalidArgument for a mimic joint or a value outside the limits.
  void setHeldPosition(std::string_view joint, double value);
  double heldPosition(int joint) const { return held_[static_cast<std::size_t>(joint)]; }
  /// Every mimic joint, parent before child; forward kinematics sets each after the others.
  const std::vector<MimicJoint>& mimicJoints() const { return mimics_; }
  /// True when the joint's position depends on the configuration: it is actuated, or it mimics
  /// an actuated joint.
  bool followsConfiguration(int joint) const;

  /// Limits of the actuated joints, for the model's input scaling.
  JointLimits limits() const;

  /// The pairs a self-collision check skips by default: links rigidly joined through fixed
  /// joints, and adjacent links, where links without collision geometry in between are skipped.
  AllowedCollisionMatrix adjacentLinks() const;

  /// Pairs the description itself allows (like an SRDF's disabled collisions), e.g. links that
  /// touch by construction.
  AllowedCollisionMatrix& allowedCollisions() { return allowed_; }
  const AllowedCollisionMatrix& allowedCollisions() const { return allowed_; }

  /// Pairs of shapes (indices into shapes()) on different links that may not touch: not
  /// adjacent, not allowed by the description and not allowed by `extra`.
  std::vector<std::pair<std::size_t, std::size_t>> selfCollisionPairs(
      const AllowedCollisionMatrix& extra) const;

 private:
  std::string name_;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<LinkShape> shapes_;
  int root_ = 0;
  std::vector<int> actuated_;
  std::vector<double> held_;  // per joint
  std::vector<MimicJoint> mimics_;
  AllowedCollisionMatrix allowed_;

  void resolveMimics();
  /// Stores `joints` in breadth-first order from the single root link and sets each link's parent
  /// joint; throws InvalidArgument naming the robot (`where`) on several roots or a cycle.
  void orderJoints(const std::string& where, const std::vector<int>& parentJointOf,
                   const std::vector<Joint>& joints);
};

/// The configuration coordinates of `robot` that are revolute joints of more than a turn (a UR
/// arm's +-2 pi): a value and that value a whole turn away are the same pose. A continuous joint's
/// range is one turn (-pi to pi), so it is not among them.
std::vector<std::size_t> coordinatesOfMoreThanATurn(const Robot& robot);

}  // namespace fastron
