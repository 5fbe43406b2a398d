#include "fastron/geometry/point_cloud.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include "fastron/core/error.h"

namespace fastron {
namespace {

constexpr std::int64_t kKeyRange = std::int64_t{1} << 20;  // voxels from the origin, per axis

/// A voxel's coordinates packed into 63 bits.
std::uint64_t voxelKey(const Eigen::Vector3d& p, double inverseVoxel) {
  std::uint64_t key = 0;
  for (int a = 0; a < 3; ++a) {
    const double cell = std::floor(p[a] * inverseVoxel);
    if (!(std::abs(cell) < static_cast<double>(kKeyRange)))
      throw InvalidArgument("voxelDownsample: a point lies more than 2^20 voxels from the origin");
    key = key << 21 | static_cast<std::uint64_t>(static_cast<std::int64_t>(cell) + kKeyRange);
  }
  return key;
}

}  // namespace

CloudPoints voxelDownsample(const CloudPoints& cloud, double voxel) {
  if (voxel == 0) return cloud;
  return voxelDownsample(cloud.points, voxel, cloud.source);
}

CloudPoints voxelDownsample(std::span<const Eigen::Vector3d> points, double voxel,
                            std::string source) {
  if (!std::isfinite(voxel) || voxel < 0)
    throw InvalidArgument("voxelDownsample: the voxel must be finite and >= 0, got " +
                          std::to_string(voxel));
  if (voxel == 0 || points.empty()) return {{points.begin(), points.end()}, std::move(source)};
  // An open-addressing table of the voxels met: twice as many slots as points, a power of 2.
  std::size_t slots = 16;
  while (slots < 2 * points.size()) slots *= 2;
  constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  std::vector<std::uint64_t> keys(slots, kEmpty);
  std::vector<std::uint32_t> voxelOf(slots);
  std::vector<Eigen::Vector3d> sums;
  std::vector<std::uint32_t> counts;
  const double inverse = 1 / voxel;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& p = points[i];
    // A NaN point would otherwise read as one more than 2^20 voxels away.
    if (!p.allFinite())
      throw InvalidArgument("voxelDownsample: point " + std::to_string(i) + " of " + source +
                            " is not finite");
    const std::uint64_t key = voxelKey(p, inverse);
    std::size_t slot = (key * 0x9E3779B97F4A7C15ULL) >> 20 & (slots - 1);
    while (keys[slot] != kEmpty && keys[slot] != key) slot = (slot + 1) & (slots - 1);
    if (keys[slot] == kEmpty) {
      keys[slot] = key;
      voxelOf[slot] = static_cast<std::uint32_t>(sums.size());
      sums.push_back(Eigen::Vector3d::Zero());
      counts.push_back(0);
    }
    sums[voxelOf[slot]] += p;
    ++counts[voxelOf[slot]];
  }
  CloudPoints out;
  out.source = std::move(source);
  out.points.reserve(sums.size());
  for (std::size_t v = 0; v < sums.size(); ++v) out.points.push_back(sums[v] / counts[v]);
  return out;
}

CloudPoints croppedToBall(const CloudPoints& cloud, const Eigen::Vector3d& centre, double radius) {
  CloudPoints out;
  out.source = cloud.source;
  const double squared = radius * radius;
  for (const Eigen::Vector3d& p : cloud.points)
    if ((p - centre).squaredNorm() <= squared) out.points.push_back(p);
  return out;
}

PointCloud sensedCloud(const CloudPoints& points, double radius, double voxel) {
  return sensedCloud(points.points, radius, voxel, points.source);
}

PointCloud sensedCloud(std::span<const Eigen::Vector3d> points, double radius, double voxel,
                       std::string source) {
  const std::string what = "point cloud " + source;
  validate(PointCloud{std::make_shared<const CloudPoints>(), radius}, what);  // the radius first
  PointCloud cloud{
      std::make_shared<const CloudPoints>(voxelDownsample(points, voxel, std::move(source))),
      radius};
  validate(cloud, what);
  return cloud;
}

}  // namespace fastron
