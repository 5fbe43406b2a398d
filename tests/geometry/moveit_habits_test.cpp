// What robots and problem files of MoveIt configurations hold that hand-written ones rarely do:
// mimic joints, continuous joints, prismatic torsos, values a hair beyond a limit, groups, and
// scenes that put the joints a plan does not move.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/moveit_request.h"
#include "fastron/geometry/point_kinematics.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/geometry/srdf.h"
#include "fastron/geometry/urdf.h"
#include "temp_dir.h"

namespace fastron {
namespace {

using ::testing::HasSubstr;

// A mobile manipulator in miniature: a prismatic torso, an arm with a continuous wrist, a gripper
// whose right finger mimics the left one, and a head that no arm group moves.
constexpr const char* kTrolleyUrdf = R"(<robot name="trolley">
  <link name="base_link"><collision><geometry><box size="0.5 0.5 0.3"/></geometry></collision></link>
  <link name="torso"><collision><geometry><box size="0.2 0.2 0.6"/></geometry></collision></link>
  <link name="head"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="upper_arm"><collision><origin xyz="0.2 0 0"/><geometry><box size="0.4 0.08 0.08"/></geometry></collision></link>
  <link name="forearm"><collision><origin xyz="0.15 0 0"/><geometry><box size="0.3 0.06 0.06"/></geometry></collision></link>
  <link name="wrist"/>
  <link name="gripper"><collision><geometry><box size="0.04 0.1 0.04"/></geometry></collision></link>
  <link name="left_finger"><collision><geometry><box size="0.05 0.01 0.02"/></geometry></collision></link>
  <link name="right_finger"><collision><geometry><box size="0.05 0.01 0.02"/></geometry></collision></link>
  <joint name="torso_lift" type="prismatic"><parent link="base_link"/><child link="torso"/>
    <origin xyz="0 0 0.45"/><axis xyz="0 0 1"/><limit lower="0" upper="0.4" effort="1" velocity="1"/></joint>
  <joint name="head_pan" type="revolute"><parent link="torso"/><child link="head"/>
    <origin xyz="0 0 0.4"/><axis xyz="0 0 1"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
  <joint name="shoulder" type="revolute"><parent link="torso"/><child link="upper_arm"/>
    <origin xyz="0.1 0 0.2"/><axis xyz="0 1 0"/><limit lower="-3.14159" upper="3.14159" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper_arm"/><child link="forearm"/>
    <origin xyz="0.4 0 0"/><axis xyz="0 1 0"/><limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="wrist_roll" type="continuous"><parent link="forearm"/><child link="wrist"/>
    <origin xyz="0.3 0 0"/><axis xyz="1 0 0"/></joint>
  <joint name="gripper_mount" type="fixed"><parent link="wrist"/><child link="gripper"/>
    <origin xyz="0.03 0 0"/></joint>
  <joint name="left_finger_joint" type="prismatic"><parent link="gripper"/><child link="left_finger"/>
    <origin xyz="0.04 0.01 0"/><axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  <joint name="right_finger_joint" type="prismatic"><parent link="gripper"/><child link="right_finger"/>
    <origin xyz="0.04 -0.01 0"/><axis xyz="0 1 0"/><limit lower="-0.04" upper="0" effort="1" velocity="1"/>
    <mimic joint="left_finger_joint" multiplier="-1" offset="0"/></joint>
</robot>)";

constexpr const char* kTrolleySrdf = R"(<robot name="trolley">
  <group name="arm"><chain base_link="torso" tip_link="gripper"/></group>
  <group name="arm_with_torso"><chain base_link="base_link" tip_link="gripper"/></group>
  <group name="gripper"><joint name="left_finger_joint"/><joint name="right_finger_joint"/></group>
  <group name="head"><link name="head"/></group>
  <disable_collisions link1="laser_link" link2="base_link" reason="Adjacent"/>
</robot>)";

Robot trolley() {
  return parseUrdf(kTrolleyUrdf, "trolley.urdf");
}

Eigen::Vector3d linkOrigin(const Robot& robot, const KinematicsData& data, const char* link) {
  return data.linkPoses[static_cast<std::size_t>(robot.linkIndex(link))].translation();
}

TEST(MimicJoints, FollowTheirJointAndAreNeverActuated) {
  Robot robot = trolley();
  EXPECT_EQ(robot.actuatedJointNames(),
            (std::vector<std::string>{"torso_lift", "head_pan", "shoulder", "elbow", "wrist_roll",
                                      "left_finger_joint"}));
  ASSERT_EQ(robot.mimicJoints().size(), 1u);
  EXPECT_EQ(robot.joints()[static_cast<std::size_t>(robot.mimicJoints()[0].source)].name,
            "left_finger_joint");
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] {
                robot.setActuatedJoints({"shoulder", "right_finger_joint"});
              }),
              HasSubstr("joint 'right_finger_joint' mimics joint 'left_finger_joint' (actuate "
                        "that one)"));
  EXPECT_THROW(robot.setHeldPosition("right_finger_joint", -0.01), InvalidArgument);

  // Actuated: the right finger moves opposite the left, by the same amount.
  KinematicsData data = makeKinematicsData(robot);
  const std::vector<double> q = {0.2, 0, 0.3, -0.4, 1.0, 0.03};
  forwardKinematics(robot, q.data(), data);
  const Eigen::Isometry3d& gripper =
      data.linkPoses[static_cast<std::size_t>(robot.linkIndex("gripper"))];
  EXPECT_LT(
      (gripper.inverse() * linkOrigin(robot, data, "left_finger") - Eigen::Vector3d(0.04, 0.04, 0))
          .norm(),
      1e-12);
  EXPECT_LT((gripper.inverse() * linkOrigin(robot, data, "right_finger") -
             Eigen::Vector3d(0.04, -0.04, 0))
                .norm(),
            1e-12);

  // Held: the mimic follows the held value.
  robot.setActuatedJoints({"torso_lift", "shoulder", "elbow", "wrist_roll"});
  robot.setHeldPosition("left_finger_joint", 0.02);
  KinematicsData held = makeKinematicsData(robot);
  const std::vector<double> arm = {0.2, 0.3, -0.4, 1.0};
  forwardKinematics(robot, arm.data(), held);
  const Eigen::Isometry3d& g = held.linkPoses[static_cast<std::size_t>(robot.linkIndex("gripper"))];
  EXPECT_LT(
      (g.inverse() * linkOrigin(robot, held, "right_finger") - Eigen::Vector3d(0.04, -0.03, 0))
          .norm(),
      1e-12);
}

// The fused control-point kinematics (double, float and the batched SIMD lanes) turn a mimic
// joint by its multiplier and offset, as forwardKinematics does.
TEST(MimicJoints, ControlPointKinematicsAgreeWithForwardKinematics) {
  std::string urdf = kTrolleyUrdf;
  const std::string mimic = "multiplier=\"-1\" offset=\"0\"";
  urdf.replace(urdf.find(mimic), mimic.size(), "multiplier=\"-0.5\" offset=\"0.01\"");
  const Robot robot = parseUrdf(urdf, "trolley.urdf");
  const std::vector<ControlPoint> points = {{"right_finger", Eigen::Vector3d(0.02, 0, 0)},
                                            {"left_finger", Eigen::Vector3d::Zero()},
                                            {"forearm", Eigen::Vector3d(0.3, 0, 0)}};
  const RobotPointKinematics fused(robot, points);
  KinematicsData data = makeKinematicsData(robot);
  Rng rng(3);
  const Configurations q = uniformConfigurations(robot.limits(), 40, rng);
  std::vector<float> batch(static_cast<std::size_t>(q.rows()) * 9);
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = q;
  fused.positionsBatch(rows.data(), static_cast<std::size_t>(q.rows()), batch.data());
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    forwardKinematics(robot, rows.row(i).data(), data);
    std::array<double, 9> exact{};
    std::array<float, 9> single{};
    fused.positions(rows.row(i).data(), exact.data());
    fused.positions(rows.row(i).data(), single.data());
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Eigen::Vector3d expected =
          data.linkPoses[static_cast<std::size_t>(robot.linkIndex(points[k].link))] *
          points[k].offset;
      for (std::size_t c = 0; c < 3; ++c) {
        EXPECT_NEAR(exact[3 * k + c], expected[static_cast<Eigen::Index>(c)], 1e-12);
        EXPECT_NEAR(single[3 * k + c], expected[static_cast<Eigen::Index>(c)], 1e-5);
        EXPECT_NEAR(batch[9 * static_cast<std::size_t>(i) + 3 * k + c],
                    expected[static_cast<Eigen::Index>(c)], 1e-5);
      }
    }
  }
}

TEST(MimicJoints, BadMimicsAreRefusedByName) {
  const auto refused = [](const std::string& from, const std::string& to) {
    std::string urdf = kTrolleyUrdf;
    urdf.replace(urdf.find(from), from.size(), to);
    try {
      parseUrdf(urdf, "bad.urdf");
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(refused("<mimic joint=\"left_finger_joint\"", "<mimic joint=\"thumb_joint\""),
              HasSubstr("bad.urdf: robot 'trolley', joint 'right_finger_joint' mimics joint "
                        "'thumb_joint', which the robot lacks"));
  EXPECT_THAT(refused("<mimic joint=\"left_finger_joint\"", "<mimic joint=\"gripper_mount\""),
              HasSubstr("mimics joint 'gripper_mount', which is fixed"));
  EXPECT_THAT(refused("multiplier=\"-1\"", "multiplier=\"nan\""),
              HasSubstr("<mimic> multiplier=\"nan\" needs 1 finite number"));
  // Two joints that follow each other follow nothing.
  const Robot base = trolley();
  std::vector<Joint> joints = base.joints();
  for (Joint& j : joints) {
    if (j.name == "left_finger_joint") j.mimic = Mimic{"right_finger_joint", 1, 0};
  }
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [&] { Robot("trolley", base.links(), joints, base.shapes()); }),
              HasSubstr("its mimics form a cycle"));
}

TEST(JointBounds, ValuesWithinTheMarginAreClampedAndContinuousJointsWrapped) {
  const Robot robot = trolley();
  const Joint& shoulder = robot.joints()[static_cast<std::size_t>(robot.jointIndex("shoulder"))];
  // MotionBenchMaker's ±pi against a URDF limit of ±3.14159.
  EXPECT_EQ(jointValueWithinLimits(shoulder, std::numbers::pi, "goal"), 3.14159);
  EXPECT_EQ(jointValueWithinLimits(shoulder, -std::numbers::pi, "goal"), -3.14159);
  EXPECT_EQ(jointValueWithinLimits(shoulder, 1.0, "goal"), 1.0);
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [&] { jointValueWithinLimits(shoulder, 3.3, "request.yaml: goal"); }),
              HasSubstr("request.yaml: goal: joint 'shoulder' at 3.300000 is outside its limits "
                        "[-3.141590, 3.141590] by more than the bounds margin 0.050000"));
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [&] { jointValueWithinLimits(shoulder, std::nan(""), "start"); }),
              HasSubstr("is not a number"));
  const Joint& wrist = robot.joints()[static_cast<std::size_t>(robot.jointIndex("wrist_roll"))];
  EXPECT_NEAR(jointValueWithinLimits(wrist, 4.0, "goal"), 4.0 - 2 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(jointValueWithinLimits(wrist, -7.0, "goal"), -7.0 + 2 * std::numbers::pi, 1e-12);
}

// A revolute joint of more than a turn (a UR arm's ±2π) is one whose value a turn away is the
// same pose; a continuous joint's range is one turn, a prismatic joint's is a length.
TEST(JointBounds, JointsOfMoreThanATurnAreNamedByCoordinate) {
  EXPECT_TRUE(coordinatesOfMoreThanATurn(trolley()).empty());  // a continuous wrist, ±π, 0.4 m
  const Robot ur3 = loadRobot("ur3");
  EXPECT_EQ(ur3.actuatedJointNames()[2], "elbow_joint");  // ±π
  EXPECT_EQ(coordinatesOfMoreThanATurn(ur3), (std::vector<std::size_t>{0, 1, 3, 4, 5}));
}

// A request plans its group; the other joints stay where the scene's robot state, and over it
// the request's start state, put them.
TEST(RequestRobot, PlansTheGroupWithTheOtherJointsWhereTheSceneHoldsThem) {
  const Robot robot = trolley();
  const Srdf srdf = parseSrdf(kTrolleySrdf, "trolley.srdf", robot);
  ASSERT_EQ(srdf.warnings.size(), 1u);  // laser_link
  EXPECT_EQ(srdf.group("arm").joints,
            (std::vector<std::string>{"shoulder", "elbow", "wrist_roll"}));
  EXPECT_EQ(srdf.group("arm_with_torso").joints,
            (std::vector<std::string>{"torso_lift", "shoulder", "elbow", "wrist_roll"}));
  EXPECT_EQ(srdf.group("gripper").joints, std::vector<std::string>{"left_finger_joint"});
  EXPECT_EQ(srdf.group("head").joints, std::vector<std::string>{"head_pan"});

  Scene scene;
  scene.robotState = {{"torso_lift", "head_pan", "left_finger_joint", "caster_wheel"},
                      {0.3, 0.5, 0.02, 9.0}};
  const PlanRequest request{"arm",
                            {{"head_pan", "shoulder", "elbow", "wrist_roll"}, {1.5001, 0, 0.1, 4}},
                            {{"shoulder", "elbow", "wrist_roll"}, {-std::numbers::pi, 1, 0}}};
  const RequestRobot planned = robotForRequest(robot, srdf.groups, scene, request, "r.yaml");
  EXPECT_TRUE(planned.warning.empty());
  const Robot& r = planned.robot;
  EXPECT_EQ(r.actuatedJointNames(), (std::vector<std::string>{"shoulder", "elbow", "wrist_roll"}));
  EXPECT_EQ(r.heldPosition(r.jointIndex("torso_lift")), 0.3);
  EXPECT_EQ(r.heldPosition(r.jointIndex("head_pan")), 1.5);  // the start state's, clamped
  EXPECT_EQ(r.heldPosition(r.jointIndex("left_finger_joint")), 0.02);
  EXPECT_EQ(r.heldPosition(r.jointIndex("right_finger_joint")), -0.02);  // its mimic
  const RequestEnds ends = requestEnds(r, request, "r.yaml");
  EXPECT_NEAR(ends.start[2], 4 - 2 * std::numbers::pi, 1e-12);
  EXPECT_EQ(ends.goal[0], -3.14159);

  // A group the SRDF lacks keeps the robot's joints, and says so.
  const RequestRobot unknown = robotForRequest(
      robot, srdf.groups, scene, PlanRequest{"manipulator", request.start, request.goal}, "r.yaml");
  EXPECT_THAT(unknown.warning, HasSubstr("r.yaml: the SRDF has no group 'manipulator'"));
  EXPECT_EQ(unknown.robot.dof(), robot.dof());
  // A held value far beyond its limits is the request's error.
  Scene far = scene;
  far.robotState.positions[0] = 0.6;
  EXPECT_THAT(test::messageOf<InvalidArgument>(
                  [&] { robotForRequest(robot, srdf.groups, far, request, "r.yaml"); }),
              HasSubstr("r.yaml: the scene's robot_state: joint 'torso_lift' at 0.600000 is "
                        "outside its limits"));
}

TEST(RequestRobot, SceneFilesGiveTheRobotState) {
  const Scene scene = parseMoveItScene(
      "world: {collision_objects: []}\n"
      "robot_state:\n"
      "  joint_state: {name: [torso_lift, head_pan], position: [0.1, -0.2]}\n"
      "  multi_dof_joint_state:\n"
      "    joint_names: [virtual_joint]\n"
      "    transforms: [{rotation: [0, 0, 0.7071068, 0.7071068], translation: [1, 2, 0]}]\n",
      "s.yaml");
  EXPECT_EQ(scene.robotState.names, (std::vector<std::string>{"torso_lift", "head_pan"}));
  EXPECT_EQ(scene.robotState.positions, (std::vector<double>{0.1, -0.2}));
  EXPECT_LT((scene.robotBase.translation() - Eigen::Vector3d(1, 2, 0)).norm(), 1e-12);
  EXPECT_LT((scene.robotBase.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(),
            1e-6);
  EXPECT_THAT(test::messageOf<FileError>([] {
                parseMoveItScene(
                    "world: {}\nrobot_state:\n  joint_state: {name: [a, b], "
                    "position: [1]}\n",
                    "s.yaml");
              }),
              HasSubstr("s.yaml:3: robot_state.joint_state: one position per name is needed"));
}

// A mobile base written into the URDF, as a planar joint (or a floating one): MoveIt plans an
// arm's group with it where the robot state puts it, so it is read as fixed at its origin, and
// the description says so.
class MultiDofJoints : public test::TempDir {};

TEST_F(MultiDofJoints, AreHeldAtTheirOriginWithAWarning) {
  for (const std::string type : {"planar", "floating"}) {
    std::string urdf = kTrolleyUrdf;
    const std::string base = R"(<link name="odom"/>
  <joint name="base_motion" type=")" +
                             type + R"("><parent link="odom"/><child link="base_link"/>
    <origin xyz="1 2 0" rpy="0 0 1.5707963267948966"/></joint>
  )";
    urdf.insert(urdf.find("<link name=\"base_link\""), base);
    const RobotDescription description =
        loadRobotDescription(write("trolley-" + type + ".urdf", urdf).string());
    const Robot& robot = description.robot;
    EXPECT_EQ(robot.dof(), 6u) << type;  // the trolley's own joints, none more
    const Joint& joint = robot.joints()[static_cast<std::size_t>(robot.jointIndex("base_motion"))];
    EXPECT_EQ(joint.type, JointType::Fixed);
    EXPECT_EQ(joint.heldMultiDof, type);
    ASSERT_EQ(description.warnings.size(), 1u);
    EXPECT_THAT(description.warnings[0],
                HasSubstr("trolley-" + type + ".urdf: joint 'base_motion' is " + type +
                          ": held at its origin"));
    // The base at the joint's origin, and the arm on it as on the trolley alone, turned a quarter
    // about z and moved to (1, 2, 0): the shoulder, 0.1 m along the trolley's x, lies along y.
    const KinematicsData home = kinematicsAtZero(robot);
    EXPECT_LT((linkOrigin(robot, home, "base_link") - Eigen::Vector3d(1, 2, 0)).norm(), 1e-12);
    EXPECT_LT((linkOrigin(robot, home, "torso") - Eigen::Vector3d(1, 2, 0.45)).norm(), 1e-12);
    EXPECT_LT((linkOrigin(robot, home, "upper_arm") - Eigen::Vector3d(1, 2.1, 0.65)).norm(), 1e-12);
    EXPECT_THAT(test::messageOf<InvalidArgument>([&] {
                  Robot(robot).setActuatedJoints({"base_motion", "shoulder"});
                }),
                HasSubstr("base_motion"));
  }
}

// The validation robots (scripts/make_validation_robots.py): their SRDFs name the catalogue's
// joints as a group, their mimics drive the gripper, and the links their SRDFs name that the URDF
// lacks are warnings.
TEST(ValidationRobots, LoadWithTheirGroupsMimicsAndWarnings) {
  const RobotDescription arm = loadRobotDescription("gripper-arm");
  EXPECT_EQ(arm.robot.dof(), 6u);
  EXPECT_EQ(arm.robot.mimicJoints().size(), 5u);
  EXPECT_EQ(arm.srdf.group("manipulator").joints, arm.robot.actuatedJointNames());
  EXPECT_EQ(arm.srdf.group("arm_and_gripper").joints.back(), "finger_joint");
  ASSERT_EQ(arm.srdf.warnings.size(), 1u);
  EXPECT_THAT(arm.srdf.warnings[0], HasSubstr("link 'camera_link'"));
  const KinematicsData home = kinematicsAtZero(arm.robot);
  EXPECT_LT((linkOrigin(arm.robot, home, "flange") - Eigen::Vector3d(0, 0.105, 1.095)).norm(),
            1e-12);

  const RobotDescription mobile = loadRobotDescription("mobile-arm");
  EXPECT_EQ(mobile.robot.dof(), 8u);
  EXPECT_EQ(mobile.srdf.group("arm_with_torso").joints, mobile.robot.actuatedJointNames());
  EXPECT_EQ(mobile.srdf.group("arm").joints.size(), 7u);
  EXPECT_EQ(mobile.srdf.warnings.size(), 2u);  // base_laser_link, estop_link
  EXPECT_EQ(mobile.robot.heldPosition(mobile.robot.jointIndex("r_gripper_finger_joint")), 0.04);
}

}  // namespace
}  // namespace fastron
