#include "fastron/geometry/kinematics.h"

#include <cmath>
#include <utility>

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

/// The coordinate axis (0 x, 1 y, 2 z) that the unit vector `axis` lies along, and its direction
/// (+1 or -1); -1 and 0 for an oblique axis.
std::pair<int, double> coordinateAxis(const Eigen::Vector3d& axis) {
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    if (axis[a] == 0 && axis[b] == 0 && std::abs(axis[k]) == 1) return {k, axis[k]};
  }
  return {-1, 0};
}

/// pose * (the joint's motion at `value`), in place: forward kinematics applies it to the parent's
/// pose times the joint origin, which costs one product fewer than composing a joint transform.
/// A turn about a coordinate axis (x, y or z, either way: the axes of URDF joints as robots are
/// written, e.g. y for the UR's shoulder and elbow, x for a wrist roll) turns two columns of the
/// pose with sin_cos.h's sine and cosine; an oblique axis multiplies by the turn's matrix from the
/// same sine and cosine. (Eigen's AngleAxis, with the C library's sincos, which branches on the
/// angle, made the UR3's forward kinematics, four joints about y, 1.3 times slower:
/// BM_ForwardKinematics.)
inline void applyMotion(const Joint& joint, double value, Eigen::Isometry3d& pose) {
  switch (joint.type) {
    case JointType::Revolute:
    case JointType::Continuous: {
      double s = 0, c = 1;
      detail::sinCos(value, s, c);
      if (const auto [k, direction] = coordinateAxis(joint.axis); k >= 0) {
        // About axis k, the columns after it in turn: (x, y) for z, (y, z) for x, (z, x) for y.
        const int a = (k + 1) % 3, b = (k + 2) % 3;
        s *= direction;
        auto r = pose.linear();
        const Eigen::Vector3d u = r.col(a), v = r.col(b);
        r.col(a) = c * u + s * v;
        r.col(b) = c * v - s * u;
      } else {
        // Rodrigues' formula, c I + s [n]x + (1 - c) n n^T, as AngleAxis::toRotationMatrix.
        const Eigen::Vector3d& n = joint.axis;
        Eigen::Matrix3d cross;
        cross << 0, -n.z(), n.y(), n.z(), 0, -n.x(), -n.y(), n.x(), 0;
        Eigen::Matrix3d turn = ((1 - c) * n) * n.transpose() + s * cross;
        turn.diagonal().array() += c;
        pose.linear() = pose.linear() * turn;
      }
      break;
    }
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
