#pragma once
// A cloud's points sorted into cubic cells: the broad phase of an exact check against a point
// cloud (which points can a shape inside a box touch?).

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

class CloudGrid {
 public:
  CloudGrid() = default;
  /// Sorts `points` into cells of edge at least `cell` (> 0), larger when the points' box would
  /// need more than 2^21 cells. A counting sort: linear in the points and cells.
  CloudGrid(std::span<const Eigen::Vector3d> points, double cell);

  std::size_t size() const { return points_.size(); }
  bool empty() const { return points_.empty(); }
  const std::vector<Eigen::Vector3d>& points() const { return points_; }  ///< sorted by cell
  double cell() const { return cell_; }
  /// The box around every point (empty for no points).
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }

  /// Calls `visit(point)` for the points of every cell that `box` overlaps and `cellNear` admits,
  /// until a call returns true; returns whether one did. `cellNear(centre, halfDiagonal)` is asked
  /// once per cell that holds points: false skips them (a shape farther than half the cell's
  /// diagonal from its centre, plus what may touch, cannot touch any). Cells in x-major order;
  /// points outside `box` may be visited (their cell overlaps it).
  template <class CellNear, class Visit>
  bool anyInBox(const Eigen::AlignedBox3d& box, CellNear&& cellNear, Visit&& visit) const;
  /// The same with every cell admitted.
  template <class Visit>
  bool anyInBox(const Eigen::AlignedBox3d& box, Visit&& visit) const {
    return anyInBox(
        box, [](const Eigen::Vector3d&, double) { return true; }, visit);
  }

 private:
  Eigen::AlignedBox3d bounds_;
  double cell_ = 1, inverseCell_ = 1;
  Eigen::Vector3i cells_ = Eigen::Vector3i::Zero();
  std::vector<std::uint32_t> start_;  // per cell, x-major, and one past the last
  std::vector<Eigen::Vector3d> points_;
};

template <class CellNear, class Visit>
bool CloudGrid::anyInBox(const Eigen::AlignedBox3d& box, CellNear&& cellNear, Visit&& visit) const {
  if (points_.empty() || !box.intersects(bounds_)) return false;
  Eigen::Vector3i lo, hi;
  for (int a = 0; a < 3; ++a) {
    const double last = cells_[a] - 1;
    lo[a] =
        static_cast<int>(std::clamp((box.min()[a] - bounds_.min()[a]) * inverseCell_, 0.0, last));
    hi[a] =
        static_cast<int>(std::clamp((box.max()[a] - bounds_.min()[a]) * inverseCell_, 0.0, last));
  }
  const double halfDiagonal = cell_ * std::sqrt(3.0) / 2;
  for (int x = lo.x(); x <= hi.x(); ++x) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      const std::size_t row = (static_cast<std::size_t>(x) * static_cast<std::size_t>(cells_.y()) +
                               static_cast<std::size_t>(y)) *
                              static_cast<std::size_t>(cells_.z());
      for (int z = lo.z(); z <= hi.z(); ++z) {
        const std::uint32_t first = start_[row + static_cast<std::size_t>(z)];
        const std::uint32_t last = start_[row + static_cast<std::size_t>(z) + 1];
        if (first == last) continue;
        const Eigen::Vector3d centre =
            bounds_.min() + cell_ * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
        if (!cellNear(centre, halfDiagonal)) continue;
        for (std::uint32_t i = first; i < last; ++i) {
          if (visit(points_[i])) return true;
        }
      }
    }
  }
  return false;
}

}  // namespace fastron
