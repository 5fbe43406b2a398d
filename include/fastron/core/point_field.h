#pragma once
// A model's point terms tabulated on grids: a collision answer whose cost does not grow with the
// support set (docs/performance.md, "Answers from tabulated point terms").
//
// A model whose kernel has only point terms (Kernel::block = 3, wholeShare = 0) scores
//   f(x) = p sum_g F_g(x_g),   F_g(y) = sum_i w_i k(|y - s_ig|^2),   p = Kernel::pointWeight,
// where x_g is the position of control point g: each F_g is a function of a point in 3-D. A
// PointField samples every F_g at the nodes of a regular grid over the box that point g reaches,
// and estimates F_g by trilinear interpolation: 8 reads per point instead of |S| kernel terms.
// Each cell keeps a bound on its interpolation error: the larger of the error measured at build
// time at its centre and the classical bound from each axis's curvature (second differences of
// the nodes at its corners), the largest of the cell's and its neighbours', times a safety
// factor, plus a floor for float rounding. Where the estimate of f lies beyond the summed
// bounds the sign is decided; where not, Model::inCollision replaces the least certain terms by
// sharper estimates, one at a time: first from the fine blocks of the least certain cells (the
// cells of largest bound are tabulated again at a finer spacing), then the terms' exact sums; when
// that does not decide either (or a point lies outside its grid) it sums every term. So a model
// with a field answers as the full sum does: the tests bisect to the decision boundary of seeded
// models to check it.

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
  /// A cell's measured error (its centre's, or its axes' curvature bound if larger) is
  /// multiplied by this before it bounds the cell: > 1, because the measures are samples, not a
  /// proof. On 20000 uniform configurations of four models of three robots (160000 or more term
  /// estimates each) the largest error reached 0.66 of its bound at 1.5; 2 with the centre's
  /// error alone let one reach 1.36 times its bound, and decided no more queries
  /// (docs/log/2026-11-30-field-reads-and-bound-slack.md).
  double errorFactor = 1.5;
  /// The most grid nodes over every point's grid (memory: 8 bytes per node).
  std::size_t maxNodes = std::size_t{1} << 25;
  /// Fine cells per edge of a coarse cell in a fine block (1: none). Fine blocks tabulate F_g
  /// again at spacing / refinement over the cells whose bounds left most of the sampled
  /// configurations undecided (then those of largest bound), until maxFineNodes: the bound of
  /// trilinear interpolation shrinks with the square of the spacing, and the queries that the
  /// cells leave undecided lie mostly in those cells (near the support points, where F_g curves
  /// most). On the mobile arm's box model (|S| 4558) they halved the share of queries left to
  /// exact sums and answered 1.5x faster, built in 1.1 s instead of 0.45 s; on models whose
  /// grids decide 90% alone they change little (docs/performance.md).
  std::uint32_t refinement = 2;
  /// The most nodes over every fine block ((refinement + 1)^3 per block, with its bounds about
  /// 5 bytes per node).
  std::size_t maxFineNodes = std::size_t{1} << 19;
  /// Fine blocks only for a field whose grids leave more than this share of the sampled
  /// configurations undecided: where they decide 90% or more (the gripper arm's and the mesh
  /// Panda's models, |S| 1088-2050; the demo's, |S| 330), fine blocks answered no faster and
  /// took 1.5-5 times as long to build.
  double fineFrom = 0.15;
  /// 1: the calling thread builds the grids alone (a background update, beside a planner on the
  /// other core); any other value: the process's helper thread takes half of them.
  unsigned threads = 0;
};

/// Throws InvalidArgument naming the field: spacing and errorFactor finite and positive (factor
/// >= 1), samples >= 1, maxNodes >= 1, refinement 1 to 16, fineFrom in [0, 1].
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
    /// Per cell: errorFactor x the largest measured interpolation error of the cell and its
    /// neighbours, plus the rounding floor.
    std::vector<float> bounds;
    /// Per cell: 0, or 1 + the index of its fine block.
    std::vector<std::uint32_t> fineBlock;
    /// The fine blocks' nodes ((refinement + 1)^3 per block, x fastest) and their cells' bounds
    /// (refinement^3 per block), block after block.
    std::vector<float> fineNodes, fineBounds;
  };

  /// `refinement`: fine cells per coarse cell edge in the grids' fine blocks.
  PointField(std::vector<Grid> grids, float roundingFloor, double spacing,
             std::uint32_t refinement);

  /// Per grid g, the estimate of F_g at x's point g (features 3g to 3g + 2) and the bound on
  /// its error: false when a point of x lies outside its grid (no estimate).
  bool estimateTerms(const float* x, float* values, float* bounds) const;

  /// +1 (collides) or -1 (free) when the grids alone decide the sign of f(x), 0 when they do
  /// not (Model::inCollision then refines the least certain terms).
  int sign(const float* x) const {
    float values[kMaxPointTerms], bounds[kMaxPointTerms], value = 0, bound = 0;
    if (!estimateTerms(x, values, bounds)) return 0;
    return signOf(values, bounds, value, bound);
  }

  /// +1, -1 or 0 as `sign`, from the grids and, where they do not decide, the fine blocks of
  /// the least certain terms (none beyond what decides).
  int signWithFineBlocks(const float* x) const;

  /// +1, -1 or 0 as the estimates `values` and their `bounds` (one per grid) decide the sign of
  /// f, leaving their sums in `value` and `bound` (what a refinement goes on from).
  int signOf(const float* values, const float* bounds, float& value, float& bound) const {
    value = 0;
    bound = 0;
    for (std::size_t g = 0; g < grids_.size(); ++g) {
      value += values[g];
      bound += bounds[g];
    }
    return signOfSums(value, bound);
  }

  /// +1, -1 or 0 as the sum of the estimates `value` and of their bounds `bound` decide the sign
  /// of f.
  static int signOfSums(float value, float bound) {
    if (value > bound) return 1;
    if (value < -bound) return -1;
    return 0;
  }

  /// Replaces the grids' estimates of the terms whose cells have fine blocks by the blocks', in
  /// the order of `order` (the terms, least certain first), until the sign is decided: returns it
  /// (or 0), leaving `values` and `bounds` the best estimates and `value` and `bound` their sums.
  int refineFinely(const float* x, const std::uint8_t* order, float* values, float* bounds,
                   float& value, float& bound) const;

  /// When point y of grid g lies in a cell with a fine block: the block's estimate of F_g(y)
  /// and its bound. False when the cell has none (or y lies outside the grid).
  bool estimateFine(std::size_t g, const float* y, float& value, float& bound) const;

  /// Where point y lies in `grid`: its cell's corner (i) and its place inside the cell (t, each
  /// in [0, 1)); false outside the grid (NaN included).
  static bool locate(const Grid& grid, const float* y, std::uint32_t i[3], float t[3]) {
    for (int a = 0; a < 3; ++a) {
      const float u = (y[a] - grid.origin[a]) * grid.inverseSpacing;
      // Negated so that NaN is outside too.
      if (!(u >= 0.0f && u < static_cast<float>(grid.cells[a]))) return false;
      i[a] = static_cast<std::uint32_t>(u);
      t[a] = u - static_cast<float>(i[a]);
    }
    return true;
  }
  /// The index of cell i in Grid::bounds.
  static std::size_t cellIndex(const Grid& grid, const std::uint32_t i[3]) {
    return i[0] + grid.cells[0] * (i[1] + std::size_t{grid.cells[1]} * i[2]);
  }
  /// The trilinear interpolation at t of the 8 values c[0], c[1] (x), c[dy], c[dy + 1] (y),
  /// c[dz] ... (z).
  static float trilinear(const float* c, std::size_t dy, std::size_t dz, const float t[3]) {
    const auto lerp = [](float a, float b, float s) { return a + s * (b - a); };
    const float y0 = lerp(lerp(c[0], c[1], t[0]), lerp(c[dy], c[dy + 1], t[0]), t[1]);
    const float y1 =
        lerp(lerp(c[dz], c[dz + 1], t[0]), lerp(c[dz + dy], c[dz + dy + 1], t[0]), t[1]);
    return lerp(y0, y1, t[2]);
  }
  /// The grid's estimate of F_g at y and its cell's bound; false outside the grid.
  static bool interpolate(const Grid& grid, const float* y, float& value, float& bound) {
    float t[3];
    std::uint32_t i[3];
    if (!locate(grid, y, i, t)) return false;
    const std::size_t nx = grid.cells[0] + 1, nxy = nx * (grid.cells[1] + 1);
    value = trilinear(grid.nodes.data() + i[0] + nx * i[1] + nxy * i[2], nx, nxy, t);
    bound = grid.bounds[cellIndex(grid, i)];
    return true;
  }

  const std::vector<Grid>& grids() const { return grids_; }
  /// Fine cells per coarse cell edge in the fine blocks.
  std::uint32_t refinement() const { return refinement_; }
  /// Fine blocks over every grid.
  std::size_t fineBlockCount() const { return fineBlocks_; }
  double spacing() const { return spacing_; }
  /// The part of every cell's bound that covers float rounding (4 FLT_EPSILON sum |w|): an exact
  /// term sum in float keeps it.
  float roundingFloor() const { return roundingFloor_; }
  std::size_t nodeCount() const;
  std::size_t memoryBytes() const;

 private:
  std::vector<Grid> grids_;
  float roundingFloor_ = 0;
  double spacing_ = 0;
  std::uint32_t refinement_ = 1;
  std::size_t fineBlocks_ = 0;  // over every grid, counted once: queries skip the blocks when 0
};

}  // namespace fastron
