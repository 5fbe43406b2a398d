// The exact oracle on point clouds: FclChecker's grid of balls answers as FCL does on one sphere
// per point, for robots of primitives and of meshes, and the GJK checker refuses clouds.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "fastron/core/error.h"
#include "fastron/geometry/clearance_bounds.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/robot_library.h"

namespace fastron {
namespace cloud_checker_test {

using ::testing::HasSubstr;

/// Points on the surfaces of two boxes in front of the robot, `spacing` apart.
std::shared_ptr<CloudPoints> surfacePoints(const Eigen::Vector3d& centre, double spacing) {
  auto cloud = std::make_shared<CloudPoints>();
  cloud->source = "test surfaces";
  for (const Eigen::Vector3d& c :
       {centre, Eigen::Vector3d(centre + Eigen::Vector3d(0, 0.5, 0.2))}) {
    const Eigen::Vector3d half(0.15, 0.2, 0.12);
    for (double x = -half.x(); x <= half.x() + 1e-9; x += spacing)
      for (double y = -half.y(); y <= half.y() + 1e-9; y += spacing)
        for (double z = -half.z(); z <= half.z() + 1e-9; z += spacing) {
          const Eigen::Vector3d p(x, y, z);
          if ((half - p.cwiseAbs()).minCoeff() < spacing / 2) cloud->points.push_back(c + p);
        }
  }
  return cloud;
}

/// The same balls as one sphere obstacle each.
Scene spheresOf(const CloudPoints& cloud, double radius) {
  Scene scene;
  for (std::size_t i = 0; i < cloud.points.size(); ++i)
    scene.add({"p" + std::to_string(i), Sphere{radius},
               Eigen::Isometry3d(Eigen::Translation3d(cloud.points[i])), std::nullopt});
  return scene;
}

Configurations randomConfigurations(const Robot& robot, std::size_t n, std::uint64_t seed) {
  const JointLimits limits = robot.limits();
  Rng rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Configurations q(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(robot.dof()));
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    for (Eigen::Index j = 0; j < q.cols(); ++j)
      q(i, j) = limits.lower()[j] + u(rng) * (limits.upper()[j] - limits.lower()[j]);
  return q;
}

void expectSameAnswers(const std::string& robotName, const Eigen::Vector3d& centre,
                       std::size_t configurations) {
  const Robot robot = loadRobot(robotName);
  const auto points = surfacePoints(centre, 0.04);
  const double radius = 0.02;
  Scene cloudScene;
  cloudScene.add(
      {"camera", PointCloud{points, radius}, Eigen::Isometry3d::Identity(), std::nullopt});
  const FclChecker onCloud(robot, cloudScene);
  const FclChecker onSpheres(robot, spheresOf(*points, radius));
  const Configurations q = randomConfigurations(robot, configurations, 7);
  std::size_t colliding = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const Eigen::VectorXd row = q.row(i);
    const std::span<const double> c(row.data(), robot.dof());
    const bool expected = onSpheres.inCollision(c);
    ASSERT_EQ(onCloud.inCollision(c), expected) << robotName << " configuration " << i;
    colliding += expected ? 1 : 0;
    if (i % 25 == 0) {
      EXPECT_NEAR(onCloud.distance(c), onSpheres.distance(c), 1e-5)
          << robotName << " configuration " << i;
    }
  }
  // Both answers are asked often enough to mean something.
  EXPECT_GT(colliding, configurations / 20) << robotName;
  EXPECT_LT(colliding, configurations * 19 / 20) << robotName;
}

TEST(CloudOracle, AnswersAsFclOnOneSpherePerPointForPrimitiveLinks) {
  expectSameAnswers("baxter", {0.7, -0.5, 0.1}, 1500);
}

TEST(CloudOracle, AnswersAsFclOnOneSpherePerPointForMeshLinks) {
  expectSameAnswers("panda-mesh", {0.45, -0.25, 0.35}, 300);
}

TEST(CloudOracle, AnEmptyCloudTouchesNothing) {
  const Robot robot = loadRobot("rod2");
  Scene scene;
  scene.add({"camera", PointCloud{std::make_shared<CloudPoints>(), 0.05},
             Eigen::Isometry3d::Identity(), std::nullopt});
  const FclChecker checker(robot, scene);
  const Eigen::Vector2d q(0, 0);
  EXPECT_FALSE(checker.inCollision(std::span<const double>(q.data(), 2)));
  EXPECT_TRUE(std::isinf(checker.distance(std::span<const double>(q.data(), 2))));
}

TEST(CloudOracle, ContactsNameTheCloudAndReplacedCloudsAreSeen) {
  const Robot robot = loadRobot("rod2");  // capsule from x = 0 to 0.5 at q = 0
  auto points = std::make_shared<CloudPoints>();
  points->points = {{0.3, 0.0, 0.0}};
  Scene scene;
  scene.add({"camera", PointCloud{points, 0.01}, Eigen::Isometry3d::Identity(), std::nullopt});
  FclChecker checker(robot, scene);
  const Eigen::Vector2d q(0, 0);
  const auto contact = checker.firstContact(std::span<const double>(q.data(), 2));
  ASSERT_TRUE(contact.has_value());
  EXPECT_EQ(contact->other, "camera");
  auto moved = std::make_shared<CloudPoints>();
  moved->points = {{0.3, 0.5, 0.0}};
  scene.setShape("camera", PointCloud{moved, 0.01});
  checker.setScene(scene);
  EXPECT_FALSE(checker.inCollision(std::span<const double>(q.data(), 2)));
}

TEST(CloudOracle, TheReachBoundHoldsEverywhere) {
  for (const std::string name : {"baxter", "panda-mesh", "ur3"}) {
    const Robot robot = loadRobot(name);
    const double reach = reachBound(robot);
    const Configurations q = randomConfigurations(robot, 300, 3);
    KinematicsData data = makeKinematicsData(robot);
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      const Eigen::VectorXd row = q.row(i);
      forwardKinematics(robot, row.data(), data);
      for (std::size_t s = 0; s < robot.shapes().size(); ++s) {
        const double far = shapePose(robot, data, s).translation().norm() +
                           boundingRadius(robot.shapes()[s].shape);
        ASSERT_LE(far, reach + 1e-9) << name << " shape " << s;
      }
    }
  }
}

TEST(CloudOracle, TheGjkCheckerRefusesClouds) {
  Scene scene;
  scene.add({"camera", PointCloud{std::make_shared<CloudPoints>(), 0.05},
             Eigen::Isometry3d::Identity(), std::nullopt});
  try {
    const GjkChecker checker(loadRobot("rod2"), scene);
    FAIL();
  } catch (const Unsupported& e) {
    EXPECT_THAT(e.what(), HasSubstr("obstacle 'camera' is a point cloud"));
  }
}

}  // namespace cloud_checker_test
}  // namespace fastron
