#pragma once
// Forward kinematics: the world pose of every link for a configuration of the actuated joints.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {

/// Per-call scratch for forwardKinematics; make one per thread with makeKinematicsData.
struct KinematicsData {
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> linkPoses;
  std::vector<double> jointPositions;  ///< per joint, actuated or held
};

KinematicsData makeKinematicsData(const Robot& robot);

/// The transform from a joint's parent link to its child at joint value `value`: the joint's
/// origin, then its motion (a rotation about, or a translation along, its axis; none if fixed).
Eigen::Isometry3d jointTransform(const Joint& joint, double value);

/// Fills data.linkPoses with every link's pose in the world, the root placed at `base`.
/// q: robot.dof() values of the actuated joints, in order. Does not allocate.
void forwardKinematics(const Robot& robot, const double* q, KinematicsData& data,
                       const Eigen::Isometry3d& base = Eigen::Isometry3d::Identity());

/// Per collision shape (robot.shapes() order): 1 if an actuated joint lies between its link and
/// the root, so that its pose depends on the configuration; 0 for shapes on the base and on links
/// joined to it through fixed or held joints, whose pose only the robot's base sets.
std::vector<std::uint8_t> shapesMovedByConfiguration(const Robot& robot);

/// Every link's pose with the actuated joints at 0 (held joints at their held values): right for
/// the links no configuration moves (shapesMovedByConfiguration), which checkers place once per
/// scene.
KinematicsData kinematicsAtZero(const Robot& robot,
                                const Eigen::Isometry3d& base = Eigen::Isometry3d::Identity());

/// World pose of a collision shape after forwardKinematics.
inline Eigen::Isometry3d shapePose(const Robot& robot, const KinematicsData& data,
                                   std::size_t shape) {
  const LinkShape& s = robot.shapes()[shape];
  return data.linkPoses[static_cast<std::size_t>(s.link)] * s.origin;
}

}  // namespace fastron
