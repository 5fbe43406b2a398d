// Sensed scenes: the time to ingest a depth camera's cloud (read from .npy bytes, down-sampled,
// the exact checker's grid built), and an exact check against it: FclChecker's grid of balls
// against FCL on one sphere obstacle per point (the same answers, checked before timing).

#include <benchmark/benchmark.h>

#include "fastron/core/active_learning.h"
#include "fastron/core/npy.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/point_cloud.h"
#include "fastron/geometry/point_cloud_file.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/geometry/scene_sensing.h"

namespace fastron {
namespace {

constexpr double kRadius = 0.01;

/// Baxter's sensed scene (data/scenes/baxter_sensed.yaml) as a camera of `width` x `height`
/// pixels above the shoulder sees it.
CloudPoints cameraCloud(int width, int height) {
  DepthCamera camera;
  camera.pose = cameraLookingAt({0.0, -0.55, 1.1}, {1.0, -0.55, -0.1});
  camera.width = width;
  camera.height = height;
  camera.horizontalFieldOfView = 1.52;
  camera.depthNoise = 0.002;
  Rng rng(5);
  return renderDepth(camera, loadScene(dataDirectory() / "scenes" / "baxter_sensed.yaml"), rng);
}

Robot baxter() {
  return loadRobot("baxter");
}

Scene cloudScene(const PointCloud& cloud) {
  Scene scene;
  scene.add({"camera", cloud, Eigen::Isometry3d::Identity(), std::nullopt});
  return scene;
}

// Read, down-sampled at the radius, and the checker's grid: what a new camera frame costs.
void BM_CloudIngest(benchmark::State& state) {
  const CloudPoints raw =
      cameraCloud(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const std::string bytes = npyBytes(raw.points.front().data(), raw.points.size(), 3);
  Scene scene = cloudScene(sensedCloud(raw, kRadius, kRadius));
  FclChecker checker(baxter(), scene);
  std::size_t kept = 0;
  for (auto _ : state) {
    const CloudFile file = parseCloudFile(bytes, CloudFormat::Npy, "frame.npy");
    PointCloud cloud = sensedCloud(file.points, kRadius, kRadius);
    kept = cloud.cloud->points.size();
    scene.setShape("camera", std::move(cloud));
    checker.setScene(scene);
  }
  state.counters["raw_points"] = static_cast<double>(raw.points.size());
  state.counters["kept_points"] = static_cast<double>(kept);
}
BENCHMARK(BM_CloudIngest)
    ->Args({424, 240})
    ->Args({640, 480})
    ->ArgNames({"width", "height"})
    ->Unit(benchmark::kMillisecond);

/// The kept balls within Baxter's reach as one sphere obstacle each.
Scene spheresOf(const PointCloud& cloud) {
  Scene scene;
  const auto& points = cloud.cloud->points;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (points[i].norm() > 1.6) continue;  // beyond Baxter's right arm: never touched
    scene.add({"p" + std::to_string(i), Sphere{cloud.radius},
               Eigen::Isometry3d(Eigen::Translation3d(points[i])), std::nullopt});
  }
  return scene;
}

// One exact check of Baxter against the cloud: range(0) 0 for the grid of balls, 1 for FCL on
// one sphere per point.
void BM_CloudCheck(benchmark::State& state) {
  const Robot robot = baxter();
  const PointCloud cloud = sensedCloud(cameraCloud(424, 240), kRadius, kRadius);
  const FclChecker grid(robot, cloudScene(cloud));
  const FclChecker spheres(robot, spheresOf(cloud));
  Rng rng(9);
  const Configurations q = uniformConfigurations(robot.limits(), 1024, rng);
  std::size_t hits = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const std::span<const double> c(q.row(i).data(), robot.dof());
    if (grid.inCollision(c) != spheres.inCollision(c)) {
      state.SkipWithError("the two checkers disagree");
      return;
    }
    hits += grid.inCollision(c);
  }
  const FclChecker& checker = state.range(0) == 0 ? grid : spheres;
  Eigen::Index i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(checker.inCollision({q.row(i).data(), robot.dof()}));
    i = (i + 1) % q.rows();
  }
  state.SetLabel(state.range(0) == 0 ? "grid of balls" : "FCL, a sphere per point");
  state.counters["in_collision"] = static_cast<double>(hits) / static_cast<double>(q.rows());
  state.counters["points"] = static_cast<double>(cloud.cloud->points.size());
}
BENCHMARK(BM_CloudCheck)->Arg(0)->Arg(1)->ArgName("spheres");

}  // namespace
}  // namespace fastron
