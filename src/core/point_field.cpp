#include "fastron/core/point_field.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>
#include <string>

#include "fastron/core/error.h"
#include "fastron/core/model.h"
#include "helper_thread.h"
#include "kernel_sums.h"

namespace fastron {

std::string_view toString(FieldAnswers answers) {
  return answers == FieldAnswers::Estimate ? "estimate" : "exact";
}

FieldAnswers parseFieldAnswers(std::string_view text) {
  if (text == "exact") return FieldAnswers::Exact;
  if (text == "estimate") return FieldAnswers::Estimate;
  throw InvalidArgument("point field answers must be 'exact' or 'estimate', got '" +
                        std::string(text) + "'");
}

void validate(const PointFieldOptions& options) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!positive(options.spacing)) {
    throw InvalidArgument("point field spacing must be finite and positive, got " +
                          std::to_string(options.spacing));
  }
  if (!(std::isfinite(options.errorFactor) && options.errorFactor >= 1)) {
    throw InvalidArgument("point field errorFactor must be finite and at least 1, got " +
                          std::to_string(options.errorFactor));
  }
  if (options.samples == 0) throw InvalidArgument("point field samples must be at least 1");
  if (options.maxNodes == 0) throw InvalidArgument("point field maxNodes must be at least 1");
  if (options.refinement < 1 || options.refinement > 16) {
    throw InvalidArgument("point field refinement must be 1 to 16, got " +
                          std::to_string(options.refinement));
  }
  if (!(options.fineFrom >= 0 && options.fineFrom <= 1)) {
    throw InvalidArgument("point field fineFrom must be in [0, 1], got " +
                          std::to_string(options.fineFrom));
  }
}

PointField::PointField(std::vector<Grid> grids, float roundingFloor, double spacing,
                       std::uint32_t refinement, FieldAnswers answers)
    : grids_(std::move(grids)),
      roundingFloor_(roundingFloor),
      spacing_(spacing),
      refinement_(refinement),
      answers_(answers) {
  const std::size_t r = refinement_;
  for (const Grid& grid : grids_) {
    const std::size_t cells = std::size_t{grid.cells[0]} * grid.cells[1] * grid.cells[2];
    const std::size_t nodes =
        std::size_t{grid.cells[0] + 1} * (grid.cells[1] + 1) * (grid.cells[2] + 1);
    if (cells == 0 || grid.nodes.size() != nodes || grid.cellTable.size() != cells) {
      throw InvalidArgument("point field grid: " + std::to_string(grid.nodes.size()) +
                            " nodes and " + std::to_string(grid.cellTable.size()) +
                            " cell records do not fit its cells");
    }
    const std::size_t blocks = grid.fineCells.size() / (r * r * r);
    bool fits = r >= 1 && grid.fineCells.size() == blocks * r * r * r &&
                grid.fineNodes.size() == blocks * (r + 1) * (r + 1) * (r + 1) &&
                (grid.fineBlock.empty() || grid.fineBlock.size() == cells);
    for (const std::uint32_t block : grid.fineBlock) fits = fits && block <= blocks;
    if (!fits) throw InvalidArgument("point field grid: its fine blocks do not fit it");
    for (const auto* table : {&grid.cellTable, &grid.fineCells}) {
      for (const Cell& cell : *table) {
        if (cell.exponent < -126) {  // Cell::scale would not be a normal float
          throw InvalidArgument("point field grid: a cell's curvature exponent " +
                                std::to_string(cell.exponent) + " is below -126");
        }
      }
    }
    fineBlocks_ += blocks;
  }
}

std::size_t PointField::nodeCount() const {
  std::size_t n = 0;
  for (const Grid& grid : grids_) n += grid.nodes.size();
  return n;
}

std::size_t PointField::memoryBytes() const {
  std::size_t n = 0;
  for (const Grid& grid : grids_) {
    n += (grid.nodes.size() + grid.fineNodes.size()) * sizeof(float) +
         (grid.cellTable.size() + grid.fineCells.size()) * sizeof(PointField::Cell) +
         grid.fineBlock.size() * sizeof(std::uint32_t);
  }
  return n;
}

bool PointField::estimateTerms(const float* x, float* values, float* bounds) const {
  // Every term's cell is located and its cache lines requested before any is read: a query
  // reads about five lines per term from grids of megabytes.
  const std::size_t terms = grids_.size();
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): the first loop fills what is read
  std::array<const float*, kMaxPointTerms> corners;
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): the same
  std::array<const Cell*, kMaxPointTerms> cellOf;
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): the same
  std::array<std::array<float, 3>, kMaxPointTerms> within;
  for (std::size_t g = 0; g < terms; ++g) {
    const Grid& grid = grids_[g];
    std::uint32_t i[3];
    if (!locate(grid, x + 3 * g, i, within[g].data())) return false;
    const std::size_t nx = grid.cells[0] + 1, nxy = nx * (grid.cells[1] + 1);
    const float* c = grid.nodes.data() + i[0] + nx * i[1] + nxy * i[2];
    corners[g] = c;
    cellOf[g] = grid.cellTable.data() + cellIndex(grid, i);
    for (const float* line : {c, c + nx, c + nxy, c + nxy + nx}) __builtin_prefetch(line);
    __builtin_prefetch(cellOf[g]);
  }
  for (std::size_t g = 0; g < terms; ++g) {
    const std::size_t nx = grids_[g].cells[0] + 1, nxy = nx * (grids_[g].cells[1] + 1);
    values[g] = estimate(corners[g], nx, nxy, *cellOf[g], within[g].data());
    bounds[g] = cellOf[g]->bound;
  }
  return true;
}

namespace {

/// The indices 0 .. terms - 1 ordered by `bounds`, largest first: the terms whose estimates are
/// least certain, which a refinement replaces first.
std::array<std::uint8_t, kMaxPointTerms> leastCertainFirst(const float* bounds, std::size_t terms) {
  std::array<std::uint8_t, kMaxPointTerms> order;
  std::iota(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(terms), 0);
  std::sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(terms),
            [&](std::uint8_t a, std::uint8_t b) { return bounds[a] > bounds[b]; });
  return order;
}

}  // namespace

int PointField::refineFinely(const float* x, const std::uint8_t* order, float* values,
                             float* bounds, float& value, float& bound) const {
  for (std::size_t k = 0; k < grids_.size(); ++k) {
    const std::size_t g = order[k];
    float fine = 0, fineBound = 0;
    if (!estimateFine(g, x + 3 * g, fine, fineBound)) continue;
    value += fine - values[g];
    bound -= bounds[g] - fineBound;
    values[g] = fine;
    bounds[g] = fineBound;
    if (const int sign = signOfSums(value, bound); sign != 0) return sign;
  }
  return 0;
}

int PointField::signWithFineBlocks(const float* x) const {
  float values[kMaxPointTerms], bounds[kMaxPointTerms], value = 0, bound = 0;
  if (!estimateTerms(x, values, bounds)) return 0;
  const int grids = signOf(values, bounds, value, bound);
  if (grids != 0 || fineBlocks_ == 0) return grids;
  const auto order = leastCertainFirst(bounds, grids_.size());
  return refineFinely(x, order.data(), values, bounds, value, bound);
}

bool PointField::estimateFine(std::size_t g, const float* y, float& value, float& bound) const {
  const Grid& grid = grids_[g];
  if (grid.fineBlock.empty()) return false;
  float t[3];
  std::uint32_t i[3];
  if (!locate(grid, y, i, t)) return false;
  const std::uint32_t block = grid.fineBlock[cellIndex(grid, i)];
  if (block == 0) return false;
  const std::size_t r = refinement_, n = r + 1;
  std::size_t at[3];
  float ft[3];
  for (int a = 0; a < 3; ++a) {
    const float u = t[a] * static_cast<float>(r);
    at[a] = std::min(static_cast<std::size_t>(u), r - 1);
    ft[a] = u - static_cast<float>(at[a]);
  }
  const std::size_t b = block - 1;
  const Cell& cell = grid.fineCells[b * r * r * r + at[0] + r * (at[1] + r * at[2])];
  value = estimate(grid.fineNodes.data() + b * n * n * n + at[0] + n * at[1] + n * n * at[2], n,
                   n * n, cell, ft);
  bound = cell.bound;
  return true;
}

namespace {

/// F_g at n points of a row along x (start, start + step, ...), four per pass of `four`.
void fieldAlongRow(const detail::SupportView& view, const std::array<float, 3>& start, float step,
                   std::size_t n, float* out) {
  std::array<float, 3 * detail::kQueriesPerPass> xs{};
  std::array<float, detail::kQueriesPerPass> f{};
  for (std::size_t i = 0; i < n; i += detail::kQueriesPerPass) {
    const std::size_t count = std::min(detail::kQueriesPerPass, n - i);
    for (std::size_t k = 0; k < detail::kQueriesPerPass; ++k) {
      const std::size_t at = i + std::min(k, count - 1);
      xs[3 * k] = start[0] + static_cast<float>(at) * step;
      xs[3 * k + 1] = start[1];
      xs[3 * k + 2] = start[2];
    }
    detail::activeKernelSums().four(view, xs.data(), f.data());
    std::copy_n(f.begin(), count, out + i);
  }
}

/// F_g at every point of `points` (x, y, z of each), written to out, four per pass of `four`.
void fieldAtPoints(const detail::SupportView& view, std::vector<float> points, float* out) {
  const std::size_t n = points.size() / 3, q = detail::kQueriesPerPass;
  const std::size_t padded = (n + q - 1) / q * q;
  for (std::size_t k = n; k < padded; ++k) {  // a short last pass repeats the first point
    points.insert(points.end(), {points[0], points[1], points[2]});
  }
  std::array<float, detail::kQueriesPerPass> f{};
  for (std::size_t i = 0; i < padded; i += q) {
    detail::activeKernelSums().four(view, points.data() + 3 * i, f.data());
    std::copy_n(f.begin(), std::min(q, n - i), out + i);
  }
}

/// The box that the samples' point g reaches, widened by a cell on every side; its nodes are
/// added to `nodes` (counted in double: a tiny spacing must not overflow the count).
PointField::Grid gridAround(const Eigen::MatrixXd& features, std::size_t g, double spacing,
                            double& nodes) {
  PointField::Grid grid;
  grid.inverseSpacing = static_cast<float>(1.0 / spacing);
  double product = 1;
  std::array<double, 3> cells{};
  for (int a = 0; a < 3; ++a) {
    const auto column = features.col(static_cast<Eigen::Index>(3 * g) + a);
    const double lo = column.minCoeff(), hi = column.maxCoeff();
    grid.origin[a] = static_cast<float>(lo - spacing);
    cells[a] = std::ceil((hi - lo) / spacing) + 2;
    product *= cells[a] + 1;
  }
  nodes += product;
  if (nodes <= static_cast<double>(std::numeric_limits<std::uint32_t>::max())) {
    for (int a = 0; a < 3; ++a) grid.cells[a] = static_cast<std::uint32_t>(cells[a]);
  }
  return grid;
}

/// The largest of each cell's value and its neighbours' (3 x 3 x 3, clipped at the grid's
/// faces), one axis at a time.
void maxOverNeighbours(std::vector<float>& values, const std::uint32_t cells[3]) {
  std::vector<float> in(values.size());
  const std::size_t stride[3] = {1, cells[0], std::size_t{cells[0]} * cells[1]};
  for (int a = 0; a < 3; ++a) {
    in.swap(values);
    for (std::size_t i = 0; i < in.size(); ++i) {
      const std::size_t at = (i / stride[a]) % cells[a];
      float m = in[i];
      if (at > 0) m = std::max(m, in[i - stride[a]]);
      if (at + 1 < cells[a]) m = std::max(m, in[i + stride[a]]);
      values[i] = m;
    }
  }
}

/// The second differences along each axis (h^2 F_aa) at every node of a block of nodes
/// (cells[b] + 1 per axis, at least 3, x fastest), axis after axis; a node on the block's face
/// across an axis, which has no node beyond it, takes its inward neighbour's.
std::vector<float> secondDifferences(const float* nodes, const std::uint32_t cells[3]) {
  const std::size_t count[3] = {cells[0] + std::size_t{1}, cells[1] + std::size_t{1},
                                cells[2] + std::size_t{1}};
  const std::size_t stride[3] = {1, count[0], count[0] * count[1]};
  const std::size_t n = stride[2] * count[2];
  std::vector<float> out(3 * n);
  for (std::size_t z = 0, i = 0; z < count[2]; ++z) {
    for (std::size_t y = 0; y < count[1]; ++y) {
      for (std::size_t x = 0; x < count[0]; ++x, ++i) {
        const std::size_t at[3] = {x, y, z};
        for (int a = 0; a < 3; ++a) {
          const std::size_t s = stride[a];
          const std::size_t centre = at[a] == 0 ? i + s : at[a] + 1 == count[a] ? i - s : i;
          out[a * n + i] = nodes[centre + s] - 2 * nodes[centre] + nodes[centre - s];
        }
      }
    }
  }
  return out;
}

/// Stores the curvatures c (h^2 F_aa / 2 per axis) in `cell` as 8-bit values of one power of
/// two, the largest within 127 of it; returns what their rounding may add to the estimate's
/// error (the difference per axis times t (1 - t), at most 1/4).
float storeCurvatures(const float c[3], PointField::Cell& cell) {
  const float largest = std::max({std::abs(c[0]), std::abs(c[1]), std::abs(c[2])});
  int exponent = 0;
  if (largest > 0) {
    std::frexp(largest / 127, &exponent);  // largest / 127 < 2^exponent
  }
  cell.exponent = static_cast<std::int8_t>(std::clamp(exponent, -126, 127));
  const float scale = cell.scale();
  float rounding = 0;
  for (int a = 0; a < 3; ++a) {
    const float units = std::clamp(std::round(c[a] / scale), -127.0f, 127.0f);
    cell.curvature[a] = static_cast<std::int8_t>(units);
    rounding += std::abs(c[a] - units * scale);
  }
  return rounding * 0.25f;
}

/// Fills the curvature correction of cell (x, y, z) of a block of nodes (cells[b] + 1 per axis):
/// per axis a, half the mean of the second differences along a at its 8 corners
/// (storeCurvatures). Returns the bound on what the correction leaves of the interpolation's error
/// where F_aa varies within the cell: (largest - smallest) / 16 of the corners' second
/// differences, summed over the axes, plus what their storage rounds off. Along an edge, linear
/// interpolation less c t (1 - t) errs by (h^2 F_aa / 2 - c) t (1 - t); where h^2 F_aa varies
/// linearly across the cell by D, it differs from the corners' mean by at most D / 2 where
/// t (1 - t) is 1/4. (Where it does not vary, what is left is of fourth order, and the centre's
/// measure covers it.) On the models of docs/performance.md the largest error reached 0.62 of its
/// bound with this measure and 1.35 times it without.
float correctCurvature(const float* differences, const std::uint32_t cells[3], std::size_t x,
                       std::size_t y, std::size_t z, PointField::Cell& cell) {
  const std::size_t nx = cells[0] + 1, nxy = nx * (cells[1] + 1), n = nxy * (cells[2] + 1);
  const std::size_t first = x + nx * y + nxy * z;
  const std::size_t corners[8] = {
      first,       first + 1,       first + nx,       first + nx + 1,
      first + nxy, first + nxy + 1, first + nxy + nx, first + nxy + nx + 1};
  float spread = 0, curvature[3];
  for (int a = 0; a < 3; ++a) {
    float sum = 0, low = std::numeric_limits<float>::max(), high = -low;
    for (const std::size_t corner : corners) {
      const float d = differences[a * n + corner];
      sum += d;
      low = std::min(low, d);
      high = std::max(high, d);
    }
    curvature[a] = sum * (0.5f / 8);
    spread += high - low;
  }
  return spread * 0.0625f + storeCurvatures(curvature, cell);
}

/// The bounds of a block's cells (cells[b] per axis) from the errors measured in each
/// (Cell::bound on entry): errorFactor x the largest of the cell's and its neighbours' (3 x 3 x 3,
/// clipped at the block's faces), plus the rounding floor.
void boundCells(PointField::Cell* table, const std::uint32_t cells[3], double errorFactor,
                float roundingFloor) {
  std::vector<float> errors(std::size_t{cells[0]} * cells[1] * cells[2]);
  for (std::size_t k = 0; k < errors.size(); ++k) errors[k] = table[k].bound;
  maxOverNeighbours(errors, cells);
  for (std::size_t k = 0; k < errors.size(); ++k) {
    table[k].bound = static_cast<float>(errorFactor) * errors[k] + roundingFloor;
  }
}

/// The error measured in cell (x, y, z) of a block of nodes (cells[b] + 1 per axis, x fastest)
/// with their secondDifferences, whose centre's F_g is `centre`: the larger of the estimate's
/// error there and what correctCurvature (which fills the cell's correction) says the correction
/// leaves.
float measureCell(const float* nodes, const float* differences, const std::uint32_t cells[3],
                  std::size_t x, std::size_t y, std::size_t z, float centre,
                  PointField::Cell& cell) {
  const float spread = correctCurvature(differences, cells, x, y, z, cell);
  const std::size_t nx = cells[0] + 1, nxy = nx * (cells[1] + 1);
  constexpr float kMiddle[3] = {0.5f, 0.5f, 0.5f};
  const float estimate = PointField::estimate(nodes + x + nx * y + nxy * z, nx, nxy, cell, kMiddle);
  return std::max(std::abs(centre - estimate), spread);
}

/// Fills the nodes of `grid` with F_g and each cell's record: its curvature correction
/// (correctCurvature) and its bound, errorFactor x the largest error measured (measureCell) at
/// the cell or a neighbour, plus a floor for float rounding. The centre alone is not enough: where
/// the curvature changes sign inside a cell (F = x^3 about its centre) the centre's error
/// vanishes and others' do not; the spread of the corners' curvatures and the neighbours' centres
/// see it. Slabs of z go to this thread and the helper.
void tabulate(PointField::Grid& grid, const detail::SupportView& view,
              const PointFieldOptions& options, float roundingFloor) {
  const double spacing = options.spacing;
  const std::size_t cx = grid.cells[0], cy = grid.cells[1], cz = grid.cells[2];
  const std::size_t nx = cx + 1, nxy = nx * (cy + 1);
  grid.nodes.assign(nxy * (cz + 1), 0.0f);
  grid.cellTable.assign(cx * cy * cz, {});
  const auto h = static_cast<float>(spacing);
  const auto position = [&](int a, std::size_t i, float shift) {
    return grid.origin[a] + (static_cast<float>(i) + shift) * h;
  };
  auto nodeSlab = [&](std::size_t z) {
    for (std::size_t y = 0; y <= cy; ++y) {
      fieldAlongRow(view, {position(0, 0, 0), position(1, y, 0), position(2, z, 0)}, h, nx,
                    grid.nodes.data() + nxy * z + nx * y);
    }
  };
  std::vector<float> differences;  // of every node, once they are all tabulated
  auto cellSlab = [&](std::size_t z) {
    std::vector<float> centres(cx);  // per slab: the two threads run slabs at once
    for (std::size_t y = 0; y < cy; ++y) {
      fieldAlongRow(view, {position(0, 0, 0.5f), position(1, y, 0.5f), position(2, z, 0.5f)}, h, cx,
                    centres.data());
      for (std::size_t x = 0; x < cx; ++x) {
        PointField::Cell& cell = grid.cellTable[x + cx * (y + cy * z)];
        cell.bound = measureCell(grid.nodes.data(), differences.data(), grid.cells, x, y, z,
                                 centres[x], cell);
      }
    }
  };
  {
    detail::HelperSession helper(options.threads != 1);
    helper.run(cz + 1, nodeSlab);
    differences = secondDifferences(grid.nodes.data(), grid.cells);
    helper.run(cz, cellSlab);
  }
  boundCells(grid.cellTable.data(), grid.cells, options.errorFactor, roundingFloor);
}

/// Fills the fine block over `cell` of `grid`: nodes ((r + 1)^3) and cells (r^3) at spacing
/// spacing / r, measured and bounded as tabulate does the grid's (the neighbours within the
/// block).
void tabulateFineBlock(const PointField::Grid& grid, std::size_t cell,
                       const detail::SupportView& term, const PointFieldOptions& options,
                       float roundingFloor, float* nodes, PointField::Cell* cells) {
  const std::size_t r = options.refinement, n = r + 1;
  const std::size_t cx = grid.cells[0], cy = grid.cells[1];
  const std::size_t index[3] = {cell % cx, (cell / cx) % cy, cell / (cx * cy)};
  const auto h = static_cast<float>(options.spacing / static_cast<double>(r));
  const auto position = [&](int a, std::size_t i, float shift) {
    return grid.origin[a] + static_cast<float>(index[a]) * static_cast<float>(options.spacing) +
           (static_cast<float>(i) + shift) * h;
  };
  // Every node, then every centre, four to a pass over the support set.
  std::vector<float> points, values(n * n * n + r * r * r);
  for (const auto& [m, shift] : {std::pair{n, 0.0f}, std::pair{r, 0.5f}}) {
    for (std::size_t z = 0; z < m; ++z) {
      for (std::size_t y = 0; y < m; ++y) {
        for (std::size_t x = 0; x < m; ++x) {
          points.insert(points.end(),
                        {position(0, x, shift), position(1, y, shift), position(2, z, shift)});
        }
      }
    }
  }
  fieldAtPoints(term, points, values.data());
  std::copy_n(values.begin(), n * n * n, nodes);
  const float* centres = values.data() + n * n * n;
  const auto fine = static_cast<std::uint32_t>(r);
  const std::uint32_t blockCells[3] = {fine, fine, fine};
  const std::vector<float> differences = secondDifferences(nodes, blockCells);
  for (std::size_t z = 0; z < r; ++z) {
    for (std::size_t y = 0; y < r; ++y) {
      for (std::size_t x = 0; x < r; ++x) {
        const std::size_t k = x + r * (y + r * z);
        cells[k].bound =
            measureCell(nodes, differences.data(), blockCells, x, y, z, centres[k], cells[k]);
      }
    }
  }
  boundCells(cells, blockCells, options.errorFactor, roundingFloor);
}

/// Per grid and cell, how much the cell's bound left the samples (rows of `features`) undecided:
/// the sum of its bound over the samples whose estimate the grids' bounds did not decide and whose
/// point lay in it. `undecided` counts those samples.
std::vector<std::vector<float>> undecidedWeight(const std::vector<PointField::Grid>& grids,
                                                const Eigen::MatrixXd& features,
                                                std::size_t& undecided) {
  const std::size_t terms = grids.size();
  std::vector<std::vector<float>> weight(terms);
  for (std::size_t g = 0; g < terms; ++g) weight[g].assign(grids[g].cellTable.size(), 0.0f);
  std::array<float, 3 * kMaxPointTerms> x{};
  std::array<float, kMaxPointTerms> values{}, bounds{};
  std::array<std::size_t, kMaxPointTerms> cells{};
  for (Eigen::Index r = 0; r < features.rows(); ++r) {
    for (std::size_t c = 0; c < 3 * terms; ++c) {
      x[c] = static_cast<float>(features(r, static_cast<Eigen::Index>(c)));
    }
    float value = 0, bound = 0;
    bool inside = true;
    for (std::size_t g = 0; g < terms; ++g) {
      std::uint32_t i[3];
      float t[3];
      inside = PointField::locate(grids[g], x.data() + 3 * g, i, t);
      if (!inside) break;
      cells[g] = PointField::cellIndex(grids[g], i);
      PointField::interpolate(grids[g], x.data() + 3 * g, values[g], bounds[g]);
      value += values[g];
      bound += bounds[g];
    }
    if (!inside || std::abs(value) > bound) continue;
    ++undecided;
    for (std::size_t g = 0; g < terms; ++g) weight[g][cells[g]] += bounds[g];
  }
  return weight;
}

/// Unless the grids decide all but options.fineFrom of the samples (rows of `features`) alone:
/// gives fine blocks to the cells over every grid that left most samples undecided
/// (undecidedWeight), then to those of largest bound, as many as options.maxFineNodes holds,
/// tabulated on this thread and the helper.
void addFineBlocks(std::vector<PointField::Grid>& grids,
                   const std::vector<detail::SupportView>& terms, const Eigen::MatrixXd& features,
                   const PointFieldOptions& options, float roundingFloor) {
  const std::size_t r = options.refinement, n = r + 1;
  const std::size_t most = options.maxFineNodes / (n * n * n);
  if (r < 2 || most == 0) return;
  std::size_t undecided = 0;
  const auto weight = undecidedWeight(grids, features, undecided);
  if (static_cast<double>(undecided) <= options.fineFrom * static_cast<double>(features.rows())) {
    return;
  }
  struct Cell {
    float weight, bound;
    std::uint32_t grid, cell;
  };
  std::vector<Cell> cells;
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const auto& table = grids[g].cellTable;
    for (std::size_t c = 0; c < table.size(); ++c) {
      // A cell whose bound is the rounding floor's is as certain as an exact sum.
      if (table[c].bound > 2 * roundingFloor) {
        cells.push_back({weight[g][c], table[c].bound, static_cast<std::uint32_t>(g),
                         static_cast<std::uint32_t>(c)});
      }
    }
  }
  const std::size_t chosen = std::min(most, cells.size());
  std::partial_sort(cells.begin(), cells.begin() + static_cast<std::ptrdiff_t>(chosen), cells.end(),
                    [](const Cell& a, const Cell& b) {
                      return a.weight != b.weight ? a.weight > b.weight : a.bound > b.bound;
                    });
  cells.resize(chosen);
  std::sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) {
    return a.grid != b.grid ? a.grid < b.grid : a.cell < b.cell;
  });
  std::vector<std::size_t> first(grids.size() + 1, 0);  // each grid's first chosen cell
  for (const Cell& c : cells) ++first[c.grid + 1];
  for (std::size_t g = 0; g < grids.size(); ++g) {
    first[g + 1] += first[g];
    const std::size_t blocks = first[g + 1] - first[g];
    if (blocks == 0) continue;
    grids[g].fineBlock.assign(grids[g].cellTable.size(), 0);
    grids[g].fineNodes.resize(blocks * n * n * n);
    grids[g].fineCells.resize(blocks * r * r * r);
  }
  for (std::size_t c = 0; c < cells.size(); ++c) {
    grids[cells[c].grid].fineBlock[cells[c].cell] =
        static_cast<std::uint32_t>(c - first[cells[c].grid] + 1);
  }
  const std::size_t chunks = std::min<std::size_t>(cells.size(), 256);
  auto chunk = [&](std::size_t k) {
    for (std::size_t c = k * cells.size() / chunks; c < (k + 1) * cells.size() / chunks; ++c) {
      PointField::Grid& grid = grids[cells[c].grid];
      const std::size_t b = c - first[cells[c].grid];
      tabulateFineBlock(grid, cells[c].cell, terms[cells[c].grid], options, roundingFloor,
                        grid.fineNodes.data() + b * n * n * n,
                        grid.fineCells.data() + b * r * r * r);
    }
  };
  detail::HelperSession helper(options.threads != 1);
  if (chunks > 0) helper.run(chunks, chunk);
}

}  // namespace

bool Model::hasOnlyPointTerms() const {
  return kernel_.block == 3 && kernel_.wholeShare == 0 && featureDim() % 3 == 0;
}

std::shared_ptr<const Model> Model::withPointField(const PointFieldOptions& options) const {
  validate(options);
  if (!hasOnlyPointTerms()) {
    throw InvalidArgument(
        "a point field tabulates a kernel of point terms of 3 features without the whole "
        "vector's term (block 3, whole share 0); this model's kernel has " +
        describeTerms(kernel_, featureDim()));
  }
  std::mt19937_64 random(options.seed);
  Configurations samples(static_cast<Eigen::Index>(options.samples),
                         static_cast<Eigen::Index>(dim()));
  for (Eigen::Index j = 0; j < samples.cols(); ++j) {
    std::uniform_real_distribution<double> value(limits().lower()[j], limits().upper()[j]);
    for (Eigen::Index i = 0; i < samples.rows(); ++i) samples(i, j) = value(random);
  }
  const Eigen::MatrixXd features = features_.map(samples);

  const std::size_t terms = featureDim() / 3;
  std::vector<PointField::Grid> grids;
  double nodes = 0;
  for (std::size_t g = 0; g < terms; ++g) {
    grids.push_back(gridAround(features, g, options.spacing, nodes));
  }
  if (nodes > static_cast<double>(options.maxNodes)) {
    char count[32];
    std::snprintf(count, sizeof count, "%.3g", nodes);
    throw InvalidArgument("a point field of spacing " + std::to_string(options.spacing) +
                          " needs " + count + " grid nodes, more than maxNodes " +
                          std::to_string(options.maxNodes) + ": choose a larger spacing");
  }
  const float roundingFloor = 4 * FLT_EPSILON * static_cast<float>(weights_.cwiseAbs().sum());
  for (std::size_t g = 0; g < terms; ++g) {
    tabulate(grids[g], termView(g), options, roundingFloor);
  }
  if (options.answers == FieldAnswers::Exact) {  // an estimate alone never reads fine blocks
    std::vector<detail::SupportView> views;
    for (std::size_t g = 0; g < terms; ++g) views.push_back(termView(g));
    addFineBlocks(grids, views, features, options, roundingFloor);
  }
  auto copy = std::make_shared<Model>(*this);
  copy->pointField_ = std::make_shared<const PointField>(
      std::move(grids), roundingFloor, options.spacing, options.refinement, options.answers);
  return copy;
}

std::shared_ptr<const Model> withFastestAnswers(std::shared_ptr<const Model> model) {
  if (!model || !model->hasOnlyPointTerms() || model->supportCount() < kPointFieldMinSupport ||
      model->pointField()) {
    return model;
  }
  PointFieldOptions options;
  options.refinement = 1;
  options.answers = FieldAnswers::Estimate;
  return model->withPointField(options);
}

detail::SupportView Model::termView(std::size_t g) const {
  detail::SupportView term = supportView();
  term.soa += 3 * g * term.padded;
  term.dim = 3;
  term.block = 0;
  term.wholeWeight = 1;
  term.pointWeight = 0;
  return term;
}

bool Model::inCollisionByField(const float* x) const {
  const PointField& field = *pointField_;
  const std::size_t terms = field.grids().size();
  static_assert(kMaxPointTerms * 3 == kMaxFeatureDimension);
  std::array<float, kMaxPointTerms> values, bounds;
  if (field.estimateTerms(x, values.data(), bounds.data())) {
    float value = 0, bound = 0;
    if (const int sign = field.signOf(values.data(), bounds.data(), value, bound); sign != 0) {
      return sign > 0;
    }
    if (field.answers() == FieldAnswers::Estimate) return value > 0;  // the tolerance taken
    auto order = leastCertainFirst(bounds.data(), terms);
    if (field.fineBlockCount() > 0) {
      const int sign =
          field.refineFinely(x, order.data(), values.data(), bounds.data(), value, bound);
      if (sign != 0) return sign > 0;
      order = leastCertainFirst(bounds.data(), terms);  // the refined terms are now the surest
    }
    // The least certain terms first, each replaced by its exact sum (a 3-D kernel sum, a term's
    // share of the full one; the rounding floor stays with it).
    for (std::size_t k = 0; k < terms; ++k) {
      const std::size_t g = order[k];
      value += detail::activeKernelSums().one(termView(g), x + 3 * g) - values[g];
      bound -= bounds[g] - field.roundingFloor();
      if (const int sign = PointField::signOfSums(value, bound); sign != 0) return sign > 0;
    }
  }
  return scoreInputFloat(x) > 0;
}

}  // namespace fastron
