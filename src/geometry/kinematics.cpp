#include "fastron/geometry/kinematics.h"

namespace fastron {

KinematicsData makeKinematicsData(const Robot& robot) {
  KinematicsData data;
  data.linkPoses.assign(robot.links().size(), Eigen::Isometry3d::Identity());
  data.jointPositions.resize(robot.joints().size());
  for (std::size_t j = 0; j < robot.joints().size(); ++j)
    data.jointPositions[j] = robot.heldPosition(static_cast<int>(j));
  return data;
}

namespace {

/// pose * (the joint's motion at `value`), in place: forward kinematics applies it to the parent's
/// pose times the joint origin, which costs one product fewer than composing a joint transform.
inline void applyMotion(const Joint& joint, double value, Eigen::Isometry3d& pose) {
  switch (joint.type) {
    case JointType::Revolute:
    case JointType::Continuous:
      pose.linear() = pose.linear() * Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
      break;
    case JointType::Prismatic:
      pose.translation() += pose.linear() * (value * joint.axis);
      break;
    case JointType::Fixed:
      break;
  }
}

}  // namespace

Eigen::Isometry3d jointTransform(const Joint& joint, double value) {
  Eigen::Isometry3d t = joint.origin;
  applyMotion(joint, value, t);
  return t;
}

void forwardKinematics(const Robot& robot, const double* q, KinematicsData& data,
                       const Eigen::Isometry3d& base) {
  const auto& actuated = robot.actuatedJoints();
  for (std::size_t i = 0; i < actuated.size(); ++i)
    data.jointPositions[static_cast<std::size_t>(actuated[i])] = q[i];
  data.linkPoses[static_cast<std::size_t>(robot.rootLink())] = base;
  const auto& joints = robot.joints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const Joint& joint = joints[j];
    Eigen::Isometry3d pose = data.linkPoses[static_cast<std::size_t>(joint.parent)] * joint.origin;
    applyMotion(joint, data.jointPositions[j], pose);
    data.linkPoses[static_cast<std::size_t>(joint.child)] = pose;
  }
}

}  // namespace fastron
