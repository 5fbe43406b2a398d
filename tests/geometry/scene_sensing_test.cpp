// The simulated depth camera and surface sampling: points lie on the obstacles' surfaces, nearer
// obstacles hide farther ones, and the density is the one asked for.

#include "fastron/geometry/scene_sensing.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fastron/core/error.h"
#include "fastron/geometry/clearance_bounds.h"

namespace fastron {
namespace sensing_test {

Scene wallAndShapes() {
  Scene scene;
  scene.add({"wall", Box{{0.1, 2.0, 2.0}}, makePose({2.0, 0, 0}), std::nullopt});
  scene.add({"ball", Sphere{0.2}, makePose({1.0, 0.3, 0.1}), std::nullopt});
  scene.add({"can", Cylinder{0.1, 0.4}, makePose({1.2, -0.4, 0.0}, {0.3, 0.2, 0}), std::nullopt});
  scene.add({"pill", Capsule{0.08, 0.3}, makePose({1.1, 0.0, -0.5}, {1.2, 0, 0}), std::nullopt});
  return scene;
}

/// The distance from `p` to the nearest obstacle's surface (0 inside is not a surface).
double surfaceDistance(const Scene& scene, const Eigen::Vector3d& p, std::string* which) {
  double best = 1e9;
  for (const Obstacle& o : scene.obstacles()) {
    const EnclosingVolume volume(o.shape, o.pose);
    const double d = volume.distanceFrom(p);
    if (d < best) {
      best = d;
      if (which != nullptr) *which = o.name;
    }
  }
  return best;
}

TEST(DepthCamera, PointsLieOnTheVisibleSurfaces) {
  const Scene scene = wallAndShapes();
  DepthCamera camera;
  camera.pose = cameraLookingAt({-0.5, 0, 0.2}, {1.5, 0, 0});
  Rng rng(1);
  const CloudPoints cloud = renderDepth(camera, scene, rng);
  ASSERT_GT(cloud.points.size(), 5000u);
  std::map<std::string, int> seen;
  for (const Eigen::Vector3d& p : cloud.points) {
    std::string which;
    ASSERT_LT(surfaceDistance(scene, p, &which), 1e-9) << p.transpose();
    // On the surface facing the camera: a step back towards it leaves every obstacle.
    const Eigen::Vector3d back = p + 1e-6 * (camera.pose.translation() - p).normalized();
    EXPECT_GT(surfaceDistance(scene, back, nullptr), 0) << p.transpose();
    ++seen[which];
  }
  for (const char* name : {"wall", "ball", "can", "pill"}) EXPECT_GT(seen[name], 50) << name;
  // The ball hides the wall behind it: no wall point lies on the ray through the ball's centre.
  const Eigen::Vector3d eye = camera.pose.translation();
  const Eigen::Vector3d toBall = (Eigen::Vector3d(1.0, 0.3, 0.1) - eye).normalized();
  for (const Eigen::Vector3d& p : cloud.points) {
    if (p.x() < 1.9) continue;  // the wall's face
    EXPECT_LT((p - eye).normalized().dot(toBall), std::cos(0.05)) << p.transpose();
  }
}

TEST(DepthCamera, NoiseMovesPointsAlongTheirRays) {
  Scene scene;
  scene.add({"wall", Box{{0.1, 4.0, 4.0}}, makePose({2.0, 0, 0}), std::nullopt});
  DepthCamera camera;
  camera.pose = cameraLookingAt({0, 0, 0}, {1, 0, 0});
  camera.depthNoise = 0.01;
  Rng rng(2);
  const CloudPoints cloud = renderDepth(camera, scene, rng);
  ASSERT_EQ(cloud.points.size(), static_cast<std::size_t>(camera.width * camera.height));
  double sum = 0, squares = 0;
  for (const auto& p : cloud.points) {
    const double error = p.x() - 1.95;  // the depth error, scaled by the ray's slope
    sum += error;
    squares += error * error;
  }
  const double n = static_cast<double>(cloud.points.size());
  EXPECT_NEAR(sum / n, 0, 0.001);
  EXPECT_NEAR(std::sqrt(squares / n), 0.0085, 0.0015);  // 1 cm along rays up to 0.6 rad off axis
  camera.width = 0;
  EXPECT_THROW((void)renderDepth(camera, scene, rng), InvalidArgument);
}

TEST(SurfacePoints, CoverEverySurfaceAtTheDensityAsked) {
  const Scene scene = wallAndShapes();
  Rng rng(3);
  const double spacing = 0.02;
  const CloudPoints cloud = surfacePoints(scene, spacing, rng);
  for (const auto& p : cloud.points) ASSERT_LT(surfaceDistance(scene, p, nullptr), 1e-9);
  // Wall: 2 * (0.2 + 0.2 + 4) m^2; the others about 0.9 m^2 together.
  const double expected = (8.8 + 0.5 + 0.38 + 0.23) / (spacing * spacing);
  EXPECT_GT(static_cast<double>(cloud.points.size()), 0.8 * expected);
  EXPECT_LT(static_cast<double>(cloud.points.size()), 1.5 * expected);
  EXPECT_THROW((void)surfacePoints(scene, 1e-6, rng), InvalidArgument);
}

}  // namespace sensing_test
}  // namespace fastron
