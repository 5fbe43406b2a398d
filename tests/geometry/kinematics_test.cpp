// Forward kinematics of the shipped robots against the landmarks of ../shared/ROBOTS.md.

#include "fastron/geometry/kinematics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <random>
#include <vector>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/robot_library.h"

namespace fastron {
namespace {

using std::numbers::pi;

Eigen::Vector3d linkPosition(const Robot& robot, const std::string& link,
                             std::vector<double> q = {}) {
  if (q.empty()) q.assign(robot.dof(), 0.0);
  KinematicsData data = makeKinematicsData(robot);
  forwardKinematics(robot, q.data(), data);
  return data.linkPoses[static_cast<std::size_t>(robot.linkIndex(link))].translation();
}

#define EXPECT_POINT_NEAR(actual, x, y, z, tolerance) \
  EXPECT_LT(((actual)-Eigen::Vector3d(x, y, z)).norm(), tolerance) << "at " << (actual).transpose()

TEST(ForwardKinematics, BaxterLandmarksAtZero) {
  const Robot baxter = loadRobot("baxter");
  ASSERT_EQ(baxter.dof(), 7u);
  EXPECT_POINT_NEAR(linkPosition(baxter, "right_upper_shoulder"), 0.064, -0.259, 0.130,
                    0.002);  // s0
  EXPECT_POINT_NEAR(linkPosition(baxter, "right_lower_shoulder"), 0.113, -0.308, 0.400,
                    0.002);                                                                   // s1
  EXPECT_POINT_NEAR(linkPosition(baxter, "right_lower_elbow"), 0.371, -0.566, 0.331, 0.002);  // e1
  EXPECT_POINT_NEAR(linkPosition(baxter, "right_lower_forearm"), 0.635, -0.830, 0.321,
                    0.002);  // w1
  EXPECT_POINT_NEAR(linkPosition(baxter, "right_hand"), 0.797, -0.992, 0.321, 0.002);
}

TEST(ForwardKinematics, Ur3FlangeAtZero) {
  EXPECT_POINT_NEAR(linkPosition(loadRobot("ur3"), "ee_link"), 0.4569, 0.19425, 0.06655, 1e-6);
}

TEST(ForwardKinematics, PandaFlangeAtZero) {
  // Every joint at 0 (joint 4 outside its limits is fine for kinematics): flange at
  // (0.088, 0, 0.333 + 0.316 + 0.384 - 0.107).
  EXPECT_POINT_NEAR(linkPosition(loadRobot("panda"), "panda_link8"), 0.088, 0, 0.926, 1e-6);
}

TEST(ForwardKinematics, PsmInsertionMovesTheShaftThroughTheRemoteCentre) {
  const Robot psm = loadRobot("psm");
  for (const double insertion : {0.0, 0.1, 0.24}) {
    // The instrument base sits 0.4318 - q3 above the RCM, the shaft tip q3 - 0.0156 below it.
    EXPECT_POINT_NEAR(linkPosition(psm, "tool_main_link", {0, 0, insertion}), 0, 0,
                      0.4318 - insertion, 1e-6);
    EXPECT_POINT_NEAR(linkPosition(psm, "tool_wrist_link", {0, 0, insertion}), 0, 0,
                      0.0156 - insertion, 1e-6);
  }
  // Yaw and pitch pivot about the RCM: the shaft line keeps passing through the origin.
  for (const auto& q :
       {std::vector<double>{0.7, 0.3, 0.15}, std::vector<double>{-1.2, -0.6, 0.2}}) {
    const Eigen::Vector3d base = linkPosition(psm, "tool_main_link", q);
    const Eigen::Vector3d tip = linkPosition(psm, "tool_wrist_link", q);
    const Eigen::Vector3d direction = (tip - base).normalized();
    EXPECT_LT((base - base.dot(direction) * direction).norm(), 1e-9);  // distance of the line to 0
    EXPECT_NEAR((tip - base).norm(), 0.4162, 1e-9);
  }
}

TEST(ForwardKinematics, RodsYawAndPitch) {
  const Robot rod2 = loadRobot("rod2");
  auto tip = [&](double yaw, double pitch) {
    KinematicsData data = makeKinematicsData(rod2);
    const double q[2] = {yaw, pitch};
    forwardKinematics(rod2, q, data);
    return Eigen::Vector3d(data.linkPoses[static_cast<std::size_t>(rod2.linkIndex("rod"))] *
                           Eigen::Vector3d(0.5, 0, 0));
  };
  EXPECT_POINT_NEAR(tip(0, 0), 0.5, 0, 0, 1e-9);
  EXPECT_POINT_NEAR(tip(0, pi / 2), 0, 0, 0.5, 1e-9);
  EXPECT_POINT_NEAR(tip(pi / 2, 0), 0, 0.5, 0, 1e-9);
  EXPECT_POINT_NEAR(linkPosition(loadRobot("rod4"), "rod2", {0, pi / 2, 0, 0}), 0, 0, 0.5, 1e-9);
}

// A joint turning leaves its own frame's origin where it is and moves nothing upstream.
TEST(ForwardKinematics, JointsMoveOnlyTheirSubtree) {
  const Robot baxter = loadRobot("baxter");
  Rng rng(3);
  const JointLimits limits = baxter.limits();
  for (int trial = 0; trial < 20; ++trial) {
    Configurations q = uniformConfigurations(limits, 1, rng);
    for (std::size_t k = 0; k < baxter.dof(); ++k) {
      std::vector<double> a(q.row(0).data(), q.row(0).data() + baxter.dof()), b = a;
      b[k] =
          std::uniform_real_distribution<double>(limits.lower()[static_cast<Eigen::Index>(k)],
                                                 limits.upper()[static_cast<Eigen::Index>(k)])(rng);
      const Joint& joint = baxter.joints()[static_cast<std::size_t>(baxter.actuatedJoints()[k])];
      const std::string child = baxter.links()[static_cast<std::size_t>(joint.child)].name;
      const std::string parent = baxter.links()[static_cast<std::size_t>(joint.parent)].name;
      EXPECT_LT((linkPosition(baxter, child, a) - linkPosition(baxter, child, b)).norm(), 1e-12);
      EXPECT_LT((linkPosition(baxter, parent, a) - linkPosition(baxter, parent, b)).norm(), 1e-12);
    }
  }
}

TEST(ForwardKinematics, HeldJointsAndBasePose) {
  Robot panda = loadRobot("panda");
  EXPECT_EQ(panda.dof(), 7u);
  EXPECT_EQ(panda.heldPosition(panda.jointIndex("panda_finger_joint1")), 0.04);
  KinematicsData data = makeKinematicsData(panda);
  const std::vector<double> q(7, 0.0);
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  base.translation() = Eigen::Vector3d(1, 2, 3);
  forwardKinematics(panda, q.data(), data, base);
  const auto left =
      data.linkPoses[static_cast<std::size_t>(panda.linkIndex("panda_leftfinger"))].translation();
  const auto right =
      data.linkPoses[static_cast<std::size_t>(panda.linkIndex("panda_rightfinger"))].translation();
  EXPECT_NEAR((left - right).norm(), 0.08, 1e-9);  // fingers held open at 0.04 each
  EXPECT_NEAR(
      data.linkPoses[static_cast<std::size_t>(panda.linkIndex("panda_link8"))].translation().z(),
      3.926, 1e-9);
  panda.setHeldPosition("panda_finger_joint1", 0.0);
  EXPECT_THROW(panda.setHeldPosition("panda_finger_joint1", 0.5), InvalidArgument);
}

// A turn about each coordinate axis, either way (sin_cos.h's sine and cosine without a branch, two
// columns turned), and about oblique axes (the turn's matrix from the same sine and cosine)
// against Eigen's AngleAxis with the C library's sine and cosine: within a few ulps at the octant
// boundaries of the reduction, at random angles, far out and beyond the bound where the C library
// takes over. (A wrong sign, octant or pair of columns is off by up to 2.)
TEST(ForwardKinematics, AJointTurnsAsEigensAngleAxisDoes) {
  std::vector<double> angles{0.0, -0.0, 1e-300, 2 * pi, -pi};
  for (int octant = -24; octant <= 24; ++octant) {
    const double boundary = octant * pi / 4;
    for (const double nudge : {-1e-9, 0.0, 1e-9}) angles.push_back(boundary + nudge);
  }
  Rng rng(71);
  std::uniform_real_distribution<double> turn(-4 * pi, 4 * pi);
  for (int k = 0; k < 2000; ++k) angles.push_back(turn(rng));
  for (const double large : {1000.5, -65536.25, 999999.0, 1.0e6 + 0.5, -3.0e7}) {
    angles.push_back(large);
  }
  Joint joint;
  joint.type = JointType::Revolute;
  joint.origin = Eigen::Translation3d(0.1, -0.2, 0.3) *
                 Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized());
  const std::vector<Eigen::Vector3d> axes{Eigen::Vector3d::UnitX(),
                                          -Eigen::Vector3d::UnitX(),
                                          Eigen::Vector3d::UnitY(),
                                          -Eigen::Vector3d::UnitY(),
                                          Eigen::Vector3d::UnitZ(),
                                          -Eigen::Vector3d::UnitZ(),
                                          Eigen::Vector3d(1, -2, 3).normalized(),
                                          Eigen::Vector3d(0, 1, 1).normalized()};
  for (const Eigen::Vector3d& axis : axes) {
    joint.axis = axis;
    for (const double angle : angles) {
      const Eigen::Matrix4d expected = (joint.origin * Eigen::AngleAxisd(angle, axis)).matrix();
      const Eigen::Matrix4d actual = jointTransform(joint, angle).matrix();
      // A few ulps of entries up to 1 (Clang's sanitizer build, without fused multiply-adds,
      // differed by two for the oblique axis), more for large angles' reduction.
      const double tolerance = 1e-15 * std::max(1.0, std::abs(angle) * 1e-6);
      EXPECT_LT((actual - expected).cwiseAbs().maxCoeff(), tolerance)
          << "axis " << axis.transpose() << ", angle " << angle;
    }
  }
}

TEST(Robot, ActuatedJointSelection) {
  Robot baxter = loadRobot("baxter");
  baxter.setActuatedJoints({"right_s0", "right_s1", "right_e0", "right_e1"});
  EXPECT_EQ(baxter.dof(), 4u);
  EXPECT_EQ(baxter.limits().upper()[1], 1.047);
  EXPECT_THROW(baxter.setActuatedJoints({"right_s0", "no_such_joint"}), InvalidArgument);
  EXPECT_THROW(baxter.setActuatedJoints({"right_hand"}), InvalidArgument);  // fixed
  EXPECT_THROW(baxter.setActuatedJoints({"right_s0", "right_s0"}), InvalidArgument);
  EXPECT_THROW(baxter.setActuatedJoints({}), InvalidArgument);
  EXPECT_EQ(baxter.dof(), 4u);  // a refused selection changes nothing
}

// The shapes whose pose a configuration changes: those downstream of an actuated joint. Checked
// against forward kinematics: a shape marked fixed keeps its pose under random configurations, one
// marked moving changes it under some.
TEST(Robot, ShapesMovedByConfigurationAreThoseDownstreamOfAnActuatedJoint) {
  Robot baxter = loadRobot("baxter");
  const auto fixedLinks = [&] {
    const std::vector<std::uint8_t> moves = shapesMovedByConfiguration(baxter);
    EXPECT_EQ(moves.size(), baxter.shapes().size());
    KinematicsData data = makeKinematicsData(baxter);
    const std::vector<double> zero(baxter.dof(), 0.0);
    forwardKinematics(baxter, zero.data(), data);
    const KinematicsData atZero = data;
    std::vector<double> largest(moves.size(), 0.0);
    Rng rng(4);
    const Configurations q = uniformConfigurations(baxter.limits(), 20, rng);
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      forwardKinematics(baxter, q.row(i).data(), data);
      for (std::size_t s = 0; s < moves.size(); ++s) {
        const Eigen::Matrix4d change =
            shapePose(baxter, data, s).matrix() - shapePose(baxter, atZero, s).matrix();
        largest[s] = std::max(largest[s], change.cwiseAbs().maxCoeff());
      }
    }
    std::vector<std::string> names;
    for (std::size_t s = 0; s < moves.size(); ++s) {
      const std::string& link =
          baxter.links()[static_cast<std::size_t>(baxter.shapes()[s].link)].name;
      if (moves[s] == 0) {
        names.push_back(link);
        EXPECT_EQ(largest[s], 0.0) << link;
      } else {
        EXPECT_GT(largest[s], 1e-3) << link;
      }
    }
    std::sort(names.begin(), names.end());
    return names;
  };
  EXPECT_EQ(fixedLinks(), (std::vector<std::string>{"base", "head", "torso"}));
  // A held joint moves nothing: without s0, the upper shoulder stays where s0's held value puts it.
  baxter.setActuatedJoints(
      {"right_s1", "right_e0", "right_e1", "right_w0", "right_w1", "right_w2"});
  EXPECT_EQ(fixedLinks(),
            (std::vector<std::string>{"base", "head", "right_upper_shoulder", "torso"}));
}

TEST(Robot, AdjacencySkipsLinksWithoutGeometry) {
  const Robot rod4 = loadRobot("rod4");
  const AllowedCollisionMatrix adjacent = rod4.adjacentLinks();
  EXPECT_TRUE(adjacent.allowed("rod1", "rod2"));  // only the geometry-less yaw2_link between them
  const Robot baxter = loadRobot("baxter");
  const AllowedCollisionMatrix b = baxter.adjacentLinks();
  EXPECT_TRUE(b.allowed("torso", "head"));                  // rigidly joined
  EXPECT_TRUE(b.allowed("right_upper_shoulder", "torso"));  // via the fixed arm mount
  EXPECT_TRUE(b.allowed("right_lower_shoulder_cover", "right_upper_elbow"));
  EXPECT_FALSE(b.allowed("right_hand", "torso"));
  EXPECT_FALSE(b.allowed("right_lower_forearm", "right_upper_shoulder"));
}

}  // namespace
}  // namespace fastron
