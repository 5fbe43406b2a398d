#pragma once
// A model's point terms tabulated on grids: a collision answer whose cost does not grow with the
// support set (docs/performance.md, "Answers from tabulated point terms").
//
// A model whose kernel has only point terms (Kernel::block = 3, wholeShare = 0) scores
//   f(x) = p sum_g F_g(x_g),   F_g(y) = sum_i w_i k(|y - s_ig|^2),   p = Kernel::pointWeight,
// where x_g is the position of control point g: each F_g is a function of a point in 3-D. A
// PointField samples every F_g at the nodes of a regular grid over the box that point g reaches,
// and estimates F_g by trilinear interpolation: 8 reads per point instead of |S| kernel terms.
// Each cell keeps a bound on its interpolation error: the largest error measured at build time at
// the centre of the cell or of a neighbour (where trilinear interpolation errs most), times a
// safety factor, plus a floor for float rounding. Where the estimate of f lies beyond the summed
// bounds the sign is decided; where not, Model::inCollision replaces the least certain terms by
// their exact sums, one at a time, and when that does not decide either (or a point lies outside
// its grid) it sums every term. So a model with a field answers as the full sum does: the tests
// bisect to the decision boundary of seeded models to check it.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// The most point terms a model has (kMaxFeatureDimension / 3), hence a field's grids.
inline constexpr std::size_t kMaxPointTerms = 64;

/// How a PointField is built. The defaults measured best on the shipped and generated robots
/// (docs/performance.md): 4 cm cells.
struct PointFieldOptions {
  /// Edge of a grid cell in feature units (metres for control points): finer cells leave fewer
  /// queries to the full sum, at 8 times the memory and build time per halving.
  double spacing = 0.04;
  /// Configurations sampled uniformly within the joint limits to find the box each point
  /// reaches; queries beyond it (widened by one cell) are answered by the full sum.
  std::size_t samples = 20000;
  std::uint64_t seed = 1;
  /// The interpolation error measured at a cell's centre is multiplied by this before it bounds
  /// the cell: > 1, because the centre is where trilinear interpolation of a smooth function errs
  /// most, not a proof that it errs least elsewhere.
  double errorFactor = 2;
  /// The most grid nodes over every point's grid (memory: 8 bytes per node).
  std::size_t maxNodes = std::size_t{1} << 25;
  /// 1: the calling thread builds the grids alone (a background update, beside a planner on the
  /// other core); any other value: the process's helper thread takes half of them.
  unsigned threads = 0;
};

/// Throws InvalidArgument naming the field: spacing and errorFactor finite and positive (factor
/// >= 1), samples >= 1, maxNodes >= 1.
void validate(const PointFieldOptions& options);

/// Immutable once built: queried from any number of threads. Built by Model::withPointField.
class PointField {
 public:
  /// One point term's grid: nodes (cells + 1 per axis, x fastest) and a bound per cell.
  struct Grid {
    float origin[3] = {0, 0, 0};
    float inverseSpacing = 1;
    std::uint32_t cells[3] = {0, 0, 0};
    std::vector<float> nodes;  ///< F_g at the nodes
    /// Per cell: errorFactor x the largest interpolation error at the centres of the cell and its
    /// neighbours, plus the rounding floor.
    std::vector<float> bounds;
  };

  PointField(std::vector<Grid> grids, float roundingFloor, double spacing);

  /// Per grid g, the estimate of F_g at x's point g (features 3g to 3g + 2) and the bound on
  /// its error: false when a point of x lies outside its grid (no estimate).
  bool estimateTerms(const float* x, float* values, float* bounds) const {
    for (std::size_t g = 0; g < grids_.size(); ++g) {
      if (!interpolate(grids_[g], x + 3 * g, values[g], bounds[g])) return false;
    }
    return true;
  }

  /// +1 (collides) or -1 (free) when the grids alone decide the sign of f(x), 0 when they do
  /// not (Model::inCollision then refines the least certain terms with their exact sums).
  int sign(const float* x) const {
    float values[kMaxPointTerms], bounds[kMaxPointTerms];
    if (!estimateTerms(x, values, bounds)) return 0;
    float value = 0, bound = 0;
    for (std::size_t g = 0; g < grids_.size(); ++g) {
      value += values[g];
      bound += bounds[g];
    }
    if (value > bound) return 1;
    if (value < -bound) return -1;
    return 0;
  }

  const std::vector<Grid>& grids() const { return grids_; }
  double spacing() const { return spacing_; }
  /// The part of every cell's bound that covers float rounding (4 FLT_EPSILON sum |w|): an exact
  /// term sum in float keeps it.
  float roundingFloor() const { return roundingFloor_; }
  std::size_t nodeCount() const;
  std::size_t memoryBytes() const;

 private:
  static bool interpolate(const Grid& grid, const float* y, float& value, float& bound) {
    float t[3];
    std::uint32_t i[3];
    for (int a = 0; a < 3; ++a) {
      const float u = (y[a] - grid.origin[a]) * grid.inverseSpacing;
      // Negated so that NaN is outside too.
      if (!(u >= 0.0f && u < static_cast<float>(grid.cells[a]))) return false;
      i[a] = static_cast<std::uint32_t>(u);
      t[a] = u - static_cast<float>(i[a]);
    }
    const std::size_t nx = grid.cells[0] + 1, nxy = nx * (grid.cells[1] + 1);
    const float* c = grid.nodes.data() + i[0] + nx * i[1] + nxy * i[2];
    const auto lerp = [](float a, float b, float s) { return a + s * (b - a); };
    const float y0 = lerp(lerp(c[0], c[1], t[0]), lerp(c[nx], c[nx + 1], t[0]), t[1]);
    const float y1 =
        lerp(lerp(c[nxy], c[nxy + 1], t[0]), lerp(c[nxy + nx], c[nxy + nx + 1], t[0]), t[1]);
    value = lerp(y0, y1, t[2]);
    bound = grid.bounds[i[0] + grid.cells[0] * (i[1] + std::size_t{grid.cells[1]} * i[2])];
    return true;
  }

  std::vector<Grid> grids_;
  float roundingFloor_ = 0;
  double spacing_ = 0;
};

}  // namespace fastron
