// MoveIt SRDF disabled collisions, and the mesh Panda that ships with its SRDF.

#include "fastron/geometry/srdf.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/robot_library.h"
#include "temp_dir.h"

namespace fastron {
namespace {

using ::testing::HasSubstr;

/// The FileError message of parsing `xml` as an SRDF for the primitive Panda.
std::string srdfError(const std::string& xml) {
  try {
    parseSrdf(xml, "bad.srdf", loadRobot("panda"));
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Srdf, ReadsTheDisabledPairs) {
  const Robot panda = loadRobot("panda");
  const Srdf srdf = parseSrdf(
      "<robot name=\"panda\">\n"
      "  <group name=\"arm\"><chain base_link=\"panda_link0\" tip_link=\"panda_link8\"/></group>\n"
      "  <disable_collisions link1=\"panda_link3\" link2=\"panda_link5\" reason=\"Never\"/>\n"
      "  <disable_collisions link1=\"panda_hand\" link2=\"panda_link6\" reason=\"Never\"/>\n"
      "</robot>\n",
      "two.srdf", panda);
  const AllowedCollisionMatrix& disabled = srdf.disabledCollisions;
  EXPECT_EQ(disabled.size(), 2u);
  EXPECT_TRUE(disabled.allowed("panda_link5", "panda_link3"));
  EXPECT_TRUE(disabled.allowed("panda_hand", "panda_link6"));
  EXPECT_FALSE(disabled.allowed("panda_hand", "panda_link5"));
  EXPECT_TRUE(srdf.warnings.empty());
}

// MoveIt warns about entries that name links the URDF lacks (a MoveIt configuration written for
// a fuller URDF than the one in use) and skips them; so do we, and say where each one was.
TEST(Srdf, EntriesNamingAbsentLinksAreSkippedWithAWarning) {
  const Srdf srdf = parseSrdf(
      "<robot name=\"panda\">\n"
      "  <disable_collisions link1=\"panda_link1\" link2=\"panda_elbow\"/>\n"
      "  <disable_collisions link1=\"panda_link3\" link2=\"panda_link5\"/>\n"
      "  <group name=\"arm\"><joint name=\"panda_joint1\"/><joint name=\"camera_joint\"/></group>\n"
      "  <end_effector name=\"eef\" parent_link=\"tool0\" group=\"hand\"/>\n"
      "  <virtual_joint name=\"world\" type=\"fixed\" parent_frame=\"world\" "
      "child_link=\"panda_link0\"/>\n"
      "</robot>\n",
      "moveit.srdf", loadRobot("panda"));
  EXPECT_EQ(srdf.disabledCollisions.size(), 1u);
  EXPECT_TRUE(srdf.disabledCollisions.allowed("panda_link3", "panda_link5"));
  EXPECT_EQ(srdf.group("arm").joints, std::vector<std::string>{"panda_joint1"});
  ASSERT_EQ(srdf.warnings.size(), 4u);
  EXPECT_THAT(srdf.warnings[0], HasSubstr("moveit.srdf:5: <end_effector> names group 'hand'"));
  EXPECT_EQ(srdf.warnings[1],
            "moveit.srdf:2: link 'panda_elbow', which robot 'panda' does not have, is named by 1 "
            "entry (the first a <disable_collisions>): skipped, as MoveIt does");
  EXPECT_THAT(srdf.warnings[2], HasSubstr("moveit.srdf:4: joint 'camera_joint'"));
  EXPECT_THAT(srdf.warnings[3], HasSubstr("moveit.srdf:5: link 'tool0'"));
}

// A link the URDF lacks is one warning, however many entries name it.
TEST(Srdf, OneWarningPerAbsentLink) {
  const Srdf srdf = parseSrdf(
      "<robot name=\"panda\">\n"
      "  <disable_collisions link1=\"panda_link1\" link2=\"camera\"/>\n"
      "  <disable_collisions link1=\"panda_link2\" link2=\"camera\"/>\n"
      "  <disable_collisions link1=\"camera\" link2=\"panda_link3\"/>\n"
      "</robot>\n",
      "camera.srdf", loadRobot("panda"));
  ASSERT_EQ(srdf.warnings.size(), 1u);
  EXPECT_THAT(srdf.warnings[0], HasSubstr("camera.srdf:2: link 'camera', which robot 'panda' does "
                                          "not have, is named by 3 entries"));
  EXPECT_EQ(srdf.disabledCollisions.size(), 0u);
}

// Groups resolve as MoveIt resolves them: joints, links (their parent joint), chains (the joints
// between the two ends) and subgroups, each joint once; fixed joints give none.
TEST(Srdf, GroupsResolveToTheirMovableJoints) {
  const Srdf srdf = parseSrdf(
      "<robot name=\"panda\">\n"
      "  <group name=\"both\"><group name=\"wrist\"/><group name=\"arm\"/></group>\n"
      "  <group name=\"arm\"><chain base_link=\"panda_link0\" tip_link=\"panda_hand\"/></group>\n"
      "  <group name=\"wrist\"><link name=\"panda_link7\"/><joint name=\"panda_joint6\"/>"
      "<joint name=\"panda_joint8\"/></group>\n"
      "  <group name=\"upper\"><chain base_link=\"panda_link3\" "
      "tip_link=\"panda_link1\"/></group>\n"
      "</robot>\n",
      "groups.srdf", loadRobot("panda"));
  EXPECT_TRUE(srdf.warnings.empty());
  const std::vector<std::string> arm = {"panda_joint1", "panda_joint2", "panda_joint3",
                                        "panda_joint4", "panda_joint5", "panda_joint6",
                                        "panda_joint7"};
  EXPECT_EQ(srdf.group("arm").joints, arm);
  EXPECT_EQ(srdf.group("wrist").joints, (std::vector<std::string>{"panda_joint7", "panda_joint6"}));
  EXPECT_EQ(
      srdf.group("both").joints,
      (std::vector<std::string>{"panda_joint7", "panda_joint6", "panda_joint1", "panda_joint2",
                                "panda_joint3", "panda_joint4", "panda_joint5"}));
  // A chain whose base lies below its tip runs up through their common ancestor.
  EXPECT_EQ(srdf.group("upper").joints, (std::vector<std::string>{"panda_joint3", "panda_joint2"}));
  try {
    srdf.group("gripper");
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("no group 'gripper' (it has: both, arm, wrist, upper)"));
  }
}

TEST(Srdf, ErrorsNameTheFileLineAndElement) {
  EXPECT_THAT(srdfError("<robot name=\"panda\">\n  <disable_collisions link1=\"a\"\n</robot>"),
              HasSubstr("bad.srdf:"));
  EXPECT_THAT(srdfError("<robot name=\"panda\">\n  <disable_collisions link1=\"a\"\n</robot>"),
              HasSubstr("malformed XML"));
  EXPECT_THAT(srdfError("<robot name=\"panda\">\n\n  <disable_collisions link1=\"panda_link1\"/>\n"
                        "</robot>"),
              HasSubstr("bad.srdf:3: <disable_collisions> needs both link1 and link2"));
  EXPECT_THAT(srdfError("<robot>\n<group/></robot>"),
              HasSubstr("bad.srdf:2: <group> needs a name attribute"));
  EXPECT_THAT(srdfError("<robot><group name=\"a\"/>\n<group name=\"a\"/></robot>"),
              HasSubstr("bad.srdf:2: <group> 'a' is defined twice"));
  EXPECT_THAT(srdfError("<robot><group name=\"a\"><group name=\"b\"/></group>\n"
                        "<group name=\"b\"><group name=\"a\"/></group></robot>"),
              HasSubstr("contains itself through its subgroups"));
  EXPECT_THAT(
      srdfError("<robot><group name=\"a\"><chain base_link=\"panda_link0\"/></group></robot>"),
      HasSubstr("<chain> needs a tip_link attribute"));
  std::string deep = "<robot>";
  for (int i = 0; i < 100; ++i)
    deep += "<group name=\"g" + std::to_string(i) + "\"><group name=\"g" + std::to_string(i + 1) +
            "\"/></group>\n";
  EXPECT_THAT(srdfError(deep + "<group name=\"g100\"/></robot>"),
              HasSubstr("subgroups nest deeper than 64"));
  EXPECT_THAT(srdfError("<semantic/>"), HasSubstr("not an SRDF file"));
  EXPECT_THAT(srdfError("not xml at all"), HasSubstr("malformed XML"));
  EXPECT_THROW(loadSrdf("/nonexistent/panda.srdf", loadRobot("panda")), FileError);
  // Another robot's name is MoveIt's warning, not an error.
  const Srdf other = parseSrdf("<robot name=\"ur3\"/>", "ur3.srdf", loadRobot("panda"));
  ASSERT_EQ(other.warnings.size(), 1u);
  EXPECT_THAT(other.warnings[0], HasSubstr("is for robot 'ur3', not 'panda'"));
}

// Baxter's MoveIt configuration as MotionBenchMaker ships it: its SRDF names links the URDF lacks
// (collision_head_link, ...), and its both_arms group is made of two subgroups.
TEST(Srdf, BaxterMoveItConfigurationLoadsWithWarnings) {
  const std::filesystem::path folder =
      std::filesystem::path(FASTRON_SHARED_DIR) / "data/baxter-moveit";
  const RobotDescription baxter =
      loadRobotDescription((folder / "baxter.urdf").string(), {}, folder / "baxter.srdf");
  EXPECT_FALSE(baxter.srdf.warnings.empty());
  EXPECT_LT(baxter.srdf.warnings.size(), 20u);  // one per absent link, not one per entry
  for (const std::string& w : baxter.srdf.warnings)
    EXPECT_THAT(w, HasSubstr("skipped, as MoveIt does"));
  EXPECT_THAT(baxter.srdf.warnings.front(), HasSubstr("link 'collision_head_link'"));
  const std::vector<std::string>& both = baxter.srdf.group("both_arms").joints;
  ASSERT_EQ(both.size(), 14u);
  EXPECT_EQ(both.front(), "right_s0");
  EXPECT_EQ(both.back(), "left_w2");
  EXPECT_EQ(baxter.srdf.group("left_arm").joints.size(), 7u);
}

class SrdfFile : public test::TempDir {};

TEST_F(SrdfFile, LoadRobotAppliesIt) {
  const auto file = write("extra.srdf",
                          "<robot name=\"panda\"><disable_collisions link1=\"panda_link0\" "
                          "link2=\"panda_hand\"/></robot>");
  const Robot plain = loadRobot("panda");
  const Robot withSrdf = loadRobot("panda", {}, file);
  EXPECT_FALSE(plain.allowedCollisions().allowed("panda_link0", "panda_hand"));
  EXPECT_TRUE(withSrdf.allowedCollisions().allowed("panda_link0", "panda_hand"));
  EXPECT_EQ(withSrdf.allowedCollisions().size(), plain.allowedCollisions().size() + 1);
}

// The mesh Panda (MotionBenchMaker's and MoveIt's) carries its SRDF's 34 pairs, and its
// kinematics equal the primitive Panda's, written independently from ROBOTS.md: every link frame
// agrees at the landmarks and at random configurations.
TEST(MeshPanda, KinematicsMatchTheIndependentPandaAndTheSrdfApplies) {
  const Robot mesh = loadRobot("panda-mesh");
  const Robot primitive = loadRobot("panda");
  ASSERT_EQ(mesh.dof(), 7u);
  EXPECT_EQ(mesh.actuatedJointNames(), primitive.actuatedJointNames());
  // The limits differ: MoveIt's URDF has Franka's hard limits (joint 1: ±2.9671), the primitive
  // Panda the datasheet's soft ones (±2.8973); the kinematics must not.
  EXPECT_GE(mesh.allowedCollisions().size(), 34u);
  EXPECT_TRUE(mesh.allowedCollisions().allowed("panda_link3", "panda_link7"));  // "Never"
  EXPECT_FALSE(mesh.allowedCollisions().allowed("panda_hand", "panda_link5"));
  for (const LinkShape& shape : mesh.shapes()) {
    EXPECT_TRUE(std::holds_alternative<Mesh>(shape.shape)) << mesh.links()[shape.link].name;
  }

  KinematicsData a = makeKinematicsData(mesh), b = makeKinematicsData(primitive);
  Rng rng(5);
  Configurations q = uniformConfigurations(mesh.limits(), 50, rng);
  q.row(0).setZero();  // the flange landmark: (0.088, 0, 0.926) at zero
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    forwardKinematics(mesh, q.row(i).data(), a);
    forwardKinematics(primitive, q.row(i).data(), b);
    for (const char* link : {"panda_link1", "panda_link3", "panda_link5", "panda_link7",
                             "panda_link8", "panda_hand"}) {
      const auto pose = [&](const Robot& r, const KinematicsData& d) {
        return d.linkPoses[static_cast<std::size_t>(r.linkIndex(link))];
      };
      EXPECT_LT((pose(mesh, a).matrix() - pose(primitive, b).matrix()).norm(), 1e-9)
          << link << " at row " << i;
    }
  }
  forwardKinematics(mesh, q.row(0).data(), a);
  EXPECT_LT((a.linkPoses[static_cast<std::size_t>(mesh.linkIndex("panda_link8"))].translation() -
             Eigen::Vector3d(0.088, 0, 0.926))
                .norm(),
            1e-6);
}

// MoveIt's "ready" state is free of self-collision with the SRDF's pairs skipped, and the
// arm folded onto its base is not.
TEST(MeshPanda, SelfCollisionWithTheSrdfPairsAllowed) {
  const Robot mesh = loadRobot("panda-mesh");
  const FclChecker checker(mesh, Scene{}, {.selfCollision = true});
  const std::vector<double> ready = {0, -0.785, 0, -2.356, 0, 1.571, 0.785};
  EXPECT_FALSE(checker.inCollision(ready));
  const std::vector<double> folded = {0, 1.7, 0, -3.0, 0, 3.7, 0};
  EXPECT_TRUE(checker.inCollision(folded));
}

}  // namespace
}  // namespace fastron
