#pragma once
// Filters that make a sensed cloud cheap to check: voxel down-sampling and cropping. Both keep
// the points' frame.

#include <Eigen/Geometry>
#include <span>
#include <string>

#include "fastron/core/export.h"
#include "fastron/geometry/shapes.h"

namespace FASTRON_API fastron {

/// One point per cube of edge `voxel` (a grid aligned with the frame's axes) that holds any: the
/// centroid of the cube's points, in the order the cubes are first met. Every dropped point lies
/// within the cube's diagonal (voxel * sqrt(3)) of the point kept for it, so the balls of the
/// down-sampled cloud, grown by that much, cover the original's (docs/geometry.md). `voxel` 0
/// keeps every point. Throws InvalidArgument for a negative or non-finite voxel, or one so small
/// that a coordinate is more than 2^20 voxels from the origin.
CloudPoints voxelDownsample(const CloudPoints& cloud, double voxel);
/// The same on points held elsewhere (a numpy array's buffer, read in place).
CloudPoints voxelDownsample(std::span<const Eigen::Vector3d> points, double voxel,
                            std::string source);

/// The points within `radius` of `centre`.
CloudPoints croppedToBall(const CloudPoints& cloud, const Eigen::Vector3d& centre, double radius);

/// A cloud obstacle from sensed points: down-sampled at `voxel` (0: not at all), a ball of
/// `radius` about each point kept. Throws InvalidArgument as validate() and voxelDownsample do.
PointCloud sensedCloud(const CloudPoints& points, double radius, double voxel);
PointCloud sensedCloud(std::span<const Eigen::Vector3d> points, double radius, double voxel,
                       std::string source);

}  // namespace fastron
