#include "fastron/geometry/kinematics.h"

#include "sin_cos.h"

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
/// A turn about z, the axis of most URDF joints (every joint of the robots shipped), turns two
/// columns with sin_cos.h's sine and cosine (the C library's sincos, which branches on the angle,
/// was half of this function); another axis takes Eigen's AngleAxis.
inline void applyMotion(const Joint& joint, double value, Eigen::Isometry3d& pose) {
  switch (joint.type) {
    case JointType::Revolute:
    case JointType::Continuous:
      if (joint.axis == Eigen::Vector3d::UnitZ()) {
        double s = 0, c = 1;
        detail::sinCos(value, s, c);
        auto r = pose.linear();
        const Eigen::Vector3d x = r.col(0), y = r.col(1);
        r.col(0) = c * x + s * y;
        r.col(1) = c * y - s * x;
      } else {
        pose.linear() = pose.linear() * Eigen::AngleAxisd(value, joint.axis).toRotationMatrix();
      }
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
  for (const MimicJoint& m : robot.mimicJoints()) {
    data.jointPositions[static_cast<std::size_t>(m.joint)] =
        m.multiplier * data.jointPositions[static_cast<std::size_t>(m.source)] + m.offset;
  }
  data.linkPoses[static_cast<std::size_t>(robot.rootLink())] = base;
  const auto& joints = robot.joints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const Joint& joint = joints[j];
    Eigen::Isometry3d pose = data.linkPoses[static_cast<std::size_t>(joint.parent)] * joint.origin;
    applyMotion(joint, data.jointPositions[j], pose);
    data.linkPoses[static_cast<std::size_t>(joint.child)] = pose;
  }
}

KinematicsData kinematicsAtZero(const Robot& robot, const Eigen::Isometry3d& base) {
  KinematicsData data = makeKinematicsData(robot);
  const std::vector<double> zero(robot.dof(), 0.0);
  forwardKinematics(robot, zero.data(), data, base);
  return data;
}

std::vector<std::uint8_t> shapesMovedByConfiguration(const Robot& robot) {
  std::vector<std::uint8_t> actuated(robot.joints().size(), 0);
  for (std::size_t j = 0; j < actuated.size(); ++j)
    actuated[j] = robot.followsConfiguration(static_cast<int>(j)) ? 1 : 0;
  // Joints come parent before child: a link moves if its joint follows the configuration or its
  // parent moves.
  std::vector<std::uint8_t> linkMoves(robot.links().size(), 0);
  for (std::size_t j = 0; j < robot.joints().size(); ++j) {
    const Joint& joint = robot.joints()[j];
    linkMoves[static_cast<std::size_t>(joint.child)] =
        actuated[j] != 0 || linkMoves[static_cast<std::size_t>(joint.parent)] != 0;
  }
  std::vector<std::uint8_t> moves;
  moves.reserve(robot.shapes().size());
  for (const LinkShape& shape : robot.shapes())
    moves.push_back(linkMoves[static_cast<std::size_t>(shape.link)]);
  return moves;
}

}  // namespace fastron
