#pragma once
// A model's point terms tabulated on grids: a collision answer whose cost does not grow with the
// support set (docs/performance.md, "Answers from tabulated point terms").
//
// A model whose kernel has only point terms (Kernel::block = 3, wholeShare = 0) scores
//   f(x) = p sum_g F_g(x_g),   F_g(y) = sum_i w_i k(|y - s_ig|^2),   p = Kernel::pointWeight,
// where x_g is the position of control point g: each F_g is a function of a point in 3-D. A
// PointField samples every F_g at the nodes of a regular grid over the box that point g reaches,
// and estimates F_g by trilinear interpolation corrected for curvature: 8 reads and a cell's
// record per point instead of |S| kernel terms. Trilinear interpolation errs by about
// h^2 F_aa t_a (1 - t_a) / 2 along each axis a (h the spacing, t_a the place in the cell); each
// cell keeps that term with F_aa from the second differences of the nodes at its corners and
// subtracts it, which leaves a quarter to a fourteenth of the error on the models measured
// (docs/performance.md). Each cell also keeps a bound on what is left: the larger of the error
// measured at build time at its centre and the spread of its corners' second differences (what
// the correction cannot follow), the largest of the cell's and its neighbours', times a safety
// factor, plus a floor for float rounding. Where the estimate of f lies beyond the summed
// bounds the sign is decided; where not, Model::inCollision replaces the least certain terms by
// sharper estimates, one at a time: first from the fine blocks of the least certain cells (the
// cells of largest bound are tabulated again at a finer spacing), then the terms' exact sums; when
// that does not decide either (or a point lies outside its grid) it sums every term. So a model
// with a field answers as the full sum does: the tests bisect to the decision boundary of seeded
// models to check it.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// The most point terms a model has (kMaxFeatureDimension / 3), hence a field's grids.
inline constexpr std::size_t kMaxPointTerms = 64;

/// How a model with a point field answers a query whose sign its grids' bounds do not decide.
enum class FieldAnswers {
  /// As the full sum: the least certain terms refined (fine blocks, then exact sums) until the
  /// sign is decided. Every answer equals the sign of Model::score.
  Exact,
  /// The sign of the grids' estimate alone, a tolerance: an answer differs from the full sum's
  /// only where f lies within the summed bounds of the estimate's cells (bounds measured at build
  /// time, as for exact answers), i.e. on the model's own decision boundary, where it is least
  /// sure of its answer anyway. On the scene models of `fastron train --robot R --scene S` 9-32 of
  /// 20000 answers differed and accuracy and TPR against FCL did not move in the fourth decimal
  /// (docs/performance.md, "The estimate alone"). No fine blocks are built.
  Estimate,
};

/// "exact" or "estimate".
std::string_view toString(FieldAnswers answers);
/// Parses "exact" or "estimate"; throws InvalidArgument naming the value otherwise.
FieldAnswers parseFieldAnswers(std::string_view text);

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
  /// A cell's measured error (its centre's, or the spread of its corners' curvatures if larger)
  /// is multiplied by this before it bounds the cell: > 1, because the measures are samples, not
  /// a proof. On 20000 uniform configurations of four models of three robots (3000 of them
  /// checked term by term, 30000 or more estimates each) the largest error reached 0.62 of its
  /// bound at 1.5; without the spread it reached 1.35 times its bound
  /// (docs/log/2026-11-30-curvature-corrected-grids.md).
  double errorFactor = 1.5;
  /// The most grid nodes over every point's grid (memory: about 12 bytes per node, its value and
  /// its cell's record).
  std::size_t maxNodes = std::size_t{1} << 25;
  /// Fine cells per edge of a coarse cell in a fine block (1: none). Fine blocks tabulate F_g
  /// again at spacing / refinement over the cells whose bounds left most of the sampled
  /// configurations undecided (then those of largest bound), until maxFineNodes: the bound of
  /// trilinear interpolation shrinks with the square of the spacing, and the queries that the
  /// cells leave undecided lie mostly in those cells (near the support points, where F_g curves
  /// most). Before the grids' curvature correction, on the mobile arm's box model (|S| 4558)
  /// they halved the share of queries left to exact sums and answered 1.5x faster; since it, the
  /// grids alone decide 86-89% on the mobile arm's models, and blocks forced on them (fineFrom
  /// 0) answered 0.95-1.15x as fast (docs/performance.md).
  std::uint32_t refinement = 2;
  /// The most nodes over every fine block ((refinement + 1)^3 per block, with its cells' records
  /// about 7 bytes per node at refinement 2).
  std::size_t maxFineNodes = std::size_t{1} << 19;
  /// Fine blocks only for a field whose grids leave more than this share of the sampled
  /// configurations undecided: where they decide 85% or more (the validation robots' and the mesh
  /// Panda's models, |S| 1088-4558; the demo's, |S| 330), fine blocks answered about as fast and
  /// took 1.5-5 times as long to build.
  double fineFrom = 0.15;
  /// 1: the calling thread builds the grids alone (a background update, beside a planner on the
  /// other core); any other value: the process's helper thread takes half of them.
  unsigned threads = 0;
  /// How queries the grids leave undecided are answered (FieldAnswers): exactly by default.
  FieldAnswers answers = FieldAnswers::Exact;
};

/// Throws InvalidArgument naming the field: spacing and errorFactor finite and positive (factor
/// >= 1), samples >= 1, maxNodes >= 1, refinement 1 to 16, fineFrom in [0, 1].
void validate(const PointFieldOptions& options);

/// Immutable once built: queried from any number of threads. Built by Model::withPointField.
class PointField {
 public:
  /// What a query reads of a cell besides its corners: 8 bytes, so that a grid's records take
  /// twice its nodes' memory, not four times (16-byte records with float curvatures made the
  /// grids' part of a query 1.05-1.8 times slower, from cache misses).
  struct Cell {
    /// errorFactor x the largest error measured of the cell and its neighbours (which includes
    /// what the curvatures' rounding to 8 bits may cost), plus the rounding floor.
    float bound = 0;
    /// Per axis a, h^2 F_aa / 2 (from the mean second difference at the cell's corners) is
    /// curvature[a] x 2^exponent: the estimate subtracts it times t_a (1 - t_a) from the
    /// trilinear interpolation.
    std::int8_t curvature[3] = {0, 0, 0};
    std::int8_t exponent = 0;

    /// 2^exponent (a normal float: PointField refuses an exponent below -126).
    float scale() const {
      return std::bit_cast<float>(static_cast<std::uint32_t>(exponent + 127) << 23);
    }
  };

  /// One point term's grid: nodes (cells + 1 per axis, x fastest) and a record per cell.
  struct Grid {
    float origin[3] = {0, 0, 0};
    float inverseSpacing = 1;
    std::uint32_t cells[3] = {0, 0, 0};
    std::vector<float> nodes;     ///< F_g at the nodes
    std::vector<Cell> cellTable;  ///< per cell, x fastest
    /// Per cell: 0, or 1 + the index of its fine block.
    std::vector<std::uint32_t> fineBlock;
    /// The fine blocks' nodes ((refinement + 1)^3 per block, x fastest) and their cells
    /// (refinement^3 per block), block after block.
    std::vector<float> fineNodes;
    std::vector<Cell> fineCells;
  };

  /// `refinement`: fine cells per coarse cell edge in the grids' fine blocks. Throws
  /// InvalidArgument when a grid's nodes, cells or fine blocks do not fit its size, or a cell's
  /// curvature exponent is below -126.
  PointField(std::vector<Grid> grids, float roundingFloor, double spacing, std::uint32_t refinement,
             FieldAnswers answers = FieldAnswers::Exact);

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
  /// The index of cell i in Grid::cellTable.
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
  /// The estimate at t in `cell` whose corners start at c (as trilinear): the trilinear
  /// interpolation less the cell's curvature correction.
  static float estimate(const float* c, std::size_t dy, std::size_t dz, const Cell& cell,
                        const float t[3]) {
    float correction = 0;
    for (int a = 0; a < 3; ++a) {
      correction += static_cast<float>(cell.curvature[a]) * t[a] * (1.0f - t[a]);
    }
    return trilinear(c, dy, dz, t) - correction * cell.scale();
  }
  /// The grid's estimate of F_g at y and its cell's bound; false outside the grid.
  static bool interpolate(const Grid& grid, const float* y, float& value, float& bound) {
    float t[3];
    std::uint32_t i[3];
    if (!locate(grid, y, i, t)) return false;
    const std::size_t nx = grid.cells[0] + 1, nxy = nx * (grid.cells[1] + 1);
    const Cell& cell = grid.cellTable[cellIndex(grid, i)];
    value = estimate(grid.nodes.data() + i[0] + nx * i[1] + nxy * i[2], nx, nxy, cell, t);
    bound = cell.bound;
    return true;
  }

  const std::vector<Grid>& grids() const { return grids_; }
  /// How Model::inCollision answers what the grids leave undecided.
  FieldAnswers answers() const { return answers_; }
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
  FieldAnswers answers_ = FieldAnswers::Exact;
  std::size_t fineBlocks_ = 0;  // over every grid, counted once: queries skip the blocks when 0
};

}  // namespace fastron
