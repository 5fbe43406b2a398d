#include "fastron/geometry/cloud_grid.h"

#include <cmath>

#include "fastron/core/error.h"

namespace fastron {

CloudGrid::CloudGrid(std::span<const Eigen::Vector3d> points, double cell) {
  if (!(cell > 0) || !std::isfinite(cell))
    throw InvalidArgument("CloudGrid: the cell edge must be positive, got " + std::to_string(cell));
  if (points.size() >= std::uint32_t{0xFFFFFFFF})
    throw InvalidArgument("CloudGrid: more than 2^32 - 1 points");
  if (points.empty()) return;
  for (const Eigen::Vector3d& p : points) bounds_.extend(p);
  const Eigen::Vector3d extent = bounds_.sizes();
  // Cells along each axis; a coarser grid when the box would need too many.
  constexpr double kMaxCells = 1 << 21;
  for (;;) {
    const Eigen::Vector3d n = (extent / cell).array().floor() + 1;
    if (n.prod() <= kMaxCells) {
      cells_ = n.cast<int>();
      break;
    }
    cell *= std::cbrt(n.prod() / kMaxCells) * 1.01;
  }
  cell_ = cell;
  inverseCell_ = 1 / cell;
  const auto total = static_cast<std::size_t>(cells_.prod());
  const auto cellOf = [&](const Eigen::Vector3d& p) {
    std::size_t index = 0;
    for (int a = 0; a < 3; ++a) {
      const int c =
          std::min(cells_[a] - 1, static_cast<int>((p[a] - bounds_.min()[a]) * inverseCell_));
      index = index * static_cast<std::size_t>(cells_[a]) + static_cast<std::size_t>(c);
    }
    return index;
  };
  // A counting sort: count per cell, offsets, then place.
  std::vector<std::uint32_t> cellIndex(points.size());
  start_.assign(total + 1, 0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    cellIndex[i] = static_cast<std::uint32_t>(cellOf(points[i]));
    ++start_[cellIndex[i] + 1];
  }
  for (std::size_t c = 0; c < total; ++c) start_[c + 1] += start_[c];
  std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
  points_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) points_[next[cellIndex[i]]++] = points[i];
}

}  // namespace fastron
