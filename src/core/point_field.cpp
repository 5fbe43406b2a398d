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
}

PointField::PointField(std::vector<Grid> grids, float roundingFloor, double spacing)
    : grids_(std::move(grids)), roundingFloor_(roundingFloor), spacing_(spacing) {
  for (const Grid& grid : grids_) {
    const std::size_t cells = std::size_t{grid.cells[0]} * grid.cells[1] * grid.cells[2];
    const std::size_t nodes =
        std::size_t{grid.cells[0] + 1} * (grid.cells[1] + 1) * (grid.cells[2] + 1);
    if (cells == 0 || grid.nodes.size() != nodes || grid.bounds.size() != cells) {
      throw InvalidArgument("point field grid: " + std::to_string(grid.nodes.size()) +
                            " nodes and " + std::to_string(grid.bounds.size()) +
                            " bounds do not fit its cells");
    }
  }
}

std::size_t PointField::nodeCount() const {
  std::size_t n = 0;
  for (const Grid& grid : grids_) n += grid.nodes.size();
  return n;
}

std::size_t PointField::memoryBytes() const {
  std::size_t n = 0;
  for (const Grid& grid : grids_) n += (grid.nodes.size() + grid.bounds.size()) * sizeof(float);
  return n;
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

/// Fills the nodes of `grid` with F_g and each cell's bound: errorFactor x the largest error of
/// trilinear interpolation at the centre of the cell or of a neighbour (|F_g(centre) - the mean
/// of its corners|), plus a floor for float rounding. The centre alone is not enough: where the
/// curvature changes sign inside a cell (F = x^3 about its centre) the centre's error vanishes
/// and others' do not; the neighbours' centres see the curvature around it. Slabs of z go to this
/// thread and the helper.
void tabulate(PointField::Grid& grid, const detail::SupportView& view,
              const PointFieldOptions& options, float roundingFloor) {
  const double spacing = options.spacing, errorFactor = options.errorFactor;
  const std::size_t cx = grid.cells[0], cy = grid.cells[1], cz = grid.cells[2];
  const std::size_t nx = cx + 1, nxy = nx * (cy + 1);
  grid.nodes.assign(nxy * (cz + 1), 0.0f);
  grid.bounds.assign(cx * cy * cz, 0.0f);
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
  auto cellSlab = [&](std::size_t z) {
    std::vector<float> centres(cx);  // per slab: the two threads run slabs at once
    for (std::size_t y = 0; y < cy; ++y) {
      fieldAlongRow(view, {position(0, 0, 0.5f), position(1, y, 0.5f), position(2, z, 0.5f)}, h, cx,
                    centres.data());
      for (std::size_t x = 0; x < cx; ++x) {
        const float* c = grid.nodes.data() + x + nx * y + nxy * z;
        const float corners = (c[0] + c[1] + c[nx] + c[nx + 1] + c[nxy] + c[nxy + 1] + c[nxy + nx] +
                               c[nxy + nx + 1]) *
                              0.125f;
        grid.bounds[x + cx * (y + cy * z)] = std::abs(centres[x] - corners);
      }
    }
  };
  {
    detail::HelperSession helper(options.threads != 1);
    helper.run(cz + 1, nodeSlab);
    helper.run(cz, cellSlab);
  }
  maxOverNeighbours(grid.bounds, grid.cells);
  for (float& bound : grid.bounds) bound = static_cast<float>(errorFactor) * bound + roundingFloor;
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
  auto copy = std::make_shared<Model>(*this);
  copy->pointField_ =
      std::make_shared<const PointField>(std::move(grids), roundingFloor, options.spacing);
  return copy;
}

std::shared_ptr<const Model> withFastestAnswers(std::shared_ptr<const Model> model) {
  if (!model || !model->hasOnlyPointTerms() || model->supportCount() < kPointFieldMinSupport ||
      model->pointField()) {
    return model;
  }
  return model->withPointField();
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
    for (std::size_t g = 0; g < terms; ++g) {
      value += values[g];
      bound += bounds[g];
    }
    if (value > bound) return true;
    if (value < -bound) return false;
    // The least certain terms first, each replaced by its exact sum (a 3-D kernel sum, a term's
    // share of the full one); the rounding floor stays with it.
    std::array<std::uint8_t, kMaxPointTerms> order;
    std::iota(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(terms), 0);
    std::sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(terms),
              [&](std::uint8_t a, std::uint8_t b) { return bounds[a] > bounds[b]; });
    for (std::size_t k = 0; k < terms; ++k) {
      const std::size_t g = order[k];
      value += detail::activeKernelSums().one(termView(g), x + 3 * g) - values[g];
      bound -= bounds[g] - field.roundingFloor();
      if (value > bound) return true;
      if (value < -bound) return false;
    }
  }
  return scoreInputFloat(x) > 0;
}

}  // namespace fastron
