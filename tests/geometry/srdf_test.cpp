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
    parseSrdfDisabledCollisions(xml, "bad.srdf", loadRobot("panda"));
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Srdf, ReadsTheDisabledPairs) {
  const Robot panda = loadRobot("panda");
  const AllowedCollisionMatrix disabled = parseSrdfDisabledCollisions(
      "<robot name=\"panda\">\n"
      "  <group name=\"arm\"><chain base_link=\"panda_link0\" tip_link=\"panda_link8\"/></group>\n"
      "  <disable_collisions link1=\"panda_link3\" link2=\"panda_link5\" reason=\"Never\"/>\n"
      "  <disable_collisions link1=\"panda_hand\" link2=\"panda_link6\" reason=\"Never\"/>\n"
      "</robot>\n",
      "two.srdf", panda);
  EXPECT_EQ(disabled.size(), 2u);
  EXPECT_TRUE(disabled.allowed("panda_link5", "panda_link3"));
  EXPECT_TRUE(disabled.allowed("panda_hand", "panda_link6"));
  EXPECT_FALSE(disabled.allowed("panda_hand", "panda_link5"));
}

TEST(Srdf, ErrorsNameTheFileLineAndElement) {
  EXPECT_THAT(srdfError("<robot name=\"panda\">\n  <disable_collisions link1=\"a\"\n</robot>"),
              HasSubstr("bad.srdf:"));
  EXPECT_THAT(srdfError("<robot name=\"panda\">\n  <disable_collisions link1=\"a\"\n</robot>"),
              HasSubstr("malformed XML"));
  EXPECT_THAT(srdfError("<robot name=\"panda\">\n"
                        "  <disable_collisions link1=\"panda_link1\" link2=\"panda_elbow\"/>\n"
                        "</robot>"),
              HasSubstr("bad.srdf:2: <disable_collisions>: robot 'panda' has no link "
                        "'panda_elbow'"));
  EXPECT_THAT(srdfError("<robot name=\"panda\">\n\n  <disable_collisions link1=\"panda_link1\"/>\n"
                        "</robot>"),
              HasSubstr("bad.srdf:3: <disable_collisions> needs both link1 and link2"));
  EXPECT_THAT(srdfError("<robot name=\"ur3\"/>"),
              HasSubstr("the SRDF is for robot 'ur3', not 'panda'"));
  EXPECT_THAT(srdfError("<semantic/>"), HasSubstr("not an SRDF file"));
  EXPECT_THAT(srdfError("not xml at all"), HasSubstr("malformed XML"));
  EXPECT_THROW(loadSrdfDisabledCollisions("/nonexistent/panda.srdf", loadRobot("panda")),
               FileError);
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
