#pragma once
// Sensing a scene as a robot would: a simulated depth camera, and surface sampling. For tests,
// demos and the sensed experiment (docs/geometry.md, "Point clouds").

#include <Eigen/Geometry>

#include "fastron/core/export.h"
#include "fastron/core/types.h"
#include "fastron/geometry/scene.h"

namespace FASTRON_API fastron {

/// A pinhole depth camera. Its frame is the optical one (as ROS's): it looks along z, x to the
/// right of the image, y down.
struct DepthCamera {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< the camera's frame in the world
  int width = 160, height = 120;                           ///< pixels
  double horizontalFieldOfView = 1.2;                      ///< radians
  double minRange = 0.1, maxRange = 5.0;                   ///< metres along the ray
  /// Standard deviation (metres) of the Gaussian noise added to each depth; 0 for none.
  double depthNoise = 0;
};

/// A camera at `eye` looking at `target`, the world's z axis up in its image. Throws
/// InvalidArgument when the two coincide.
Eigen::Isometry3d cameraLookingAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target);

/// What the camera sees of the scene: for every pixel whose ray meets an obstacle within range,
/// the nearest point met (an obstacle hides what lies behind it, and its own far side), in the
/// world frame, moved along the ray by the depth noise drawn from `rng`. Boxes, spheres,
/// cylinders, capsules and meshes are seen; point clouds are not (they are what a camera gives).
/// Throws InvalidArgument for a camera without pixels, a field of view outside (0, pi) or a range
/// that is empty or not finite.
CloudPoints renderDepth(const DepthCamera& camera, const Scene& scene, Rng& rng);

/// Points on the surfaces of the scene's obstacles (world frame), about `spacing` apart: what a
/// camera circling every obstacle would see, for trying a scene as a cloud. Throws
/// InvalidArgument for a spacing that is not positive, or that would need more than 50 million
/// points.
CloudPoints surfacePoints(const Scene& scene, double spacing, Rng& rng);

}  // namespace fastron
