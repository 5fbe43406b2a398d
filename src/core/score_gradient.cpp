// Model::scoreGradient: f(q) and df/dq, for trajectory optimisation and repair (issue 53).
//
// f(q) = sum_i alpha_i k(x(q), s_i). With the one-term kernel k = k(|x - s|^2),
//   dk/dx = 2 k'(|x - s|^2) (x - s);
// with point terms k = W k(|x - s|^2) + P sum_g k(|x_g - s_g|^2),
//   dk/dx = 2 W k'(|x - s|^2) (x - s) + 2 P k'(|x_g - s_g|^2) (x_g - s_g) on each block g;
// and df/dq = J(q)^T df/dx, J the features' Jacobian (feature_map.h). The float sums are the
// kernel sums' (kernel_sums_impl.h, one pass per query on the path in use); the double one is
// the reference.

#include <algorithm>
#include <array>
#include <vector>

#include "fastron/core/error.h"
#include "fastron/core/model.h"
#include "kernel_sums.h"

namespace fastron {

static_assert(detail::kMaxFeatures == kMaxFeatureDimension);

double Model::scoreGradientInto(const double* q, double* jacobian, double* gradient) const {
  const std::size_t d = featureDim(), n = dim();
  // NOLINTBEGIN(cppcoreguidelines-pro-type-member-init): filled before they are read
  std::array<double, kMaxFeatureDimension> x;
  std::array<float, kMaxFeatureDimension> xf, dfdx;
  // NOLINTEND(cppcoreguidelines-pro-type-member-init)
  features_.jacobian(q, x.data(), jacobian);  // d rows of n values
  for (std::size_t c = 0; c < d; ++c) xf[c] = static_cast<float>(x[c]);
  const float f = detail::activeKernelSums().gradient(supportView(), xf.data(), dfdx.data());
  // df/dq = J^T df/dx
  std::fill_n(gradient, n, 0.0);
  for (std::size_t c = 0; c < d; ++c) {
    const double slope = dfdx[c];
    for (std::size_t j = 0; j < n; ++j) gradient[j] += jacobian[c * n + j] * slope;
  }
  return f;
}

Model::ScoreGradient Model::scoreGradient(std::span<const double> q) const {
  checkConfiguration(q, dim());
  std::vector<double> jacobian(featureDim() * dim());
  ScoreGradient out{0, Eigen::VectorXd(static_cast<Eigen::Index>(dim()))};
  out.score = scoreGradientInto(q.data(), jacobian.data(), out.gradient.data());
  return out;
}

Model::ScoreGradient Model::scoreGradientExact(std::span<const double> q) const {
  checkConfiguration(q, dim());
  const std::size_t d = featureDim(), n = dim();
  // NOLINTBEGIN(cppcoreguidelines-pro-type-member-init): filled before they are read
  std::array<double, kMaxFeatureDimension> x, diff, dfdx;
  // NOLINTEND(cppcoreguidelines-pro-type-member-init)
  Eigen::MatrixXd jacobian(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(d));
  // The map writes d x n row by row: the transposed view, column-major n x d.
  features_.jacobian(q.data(), x.data(), jacobian.data());
  std::fill_n(dfdx.begin(), d, 0.0);
  const std::size_t block = kernel_.block;
  const double wholeWeight = kernel_.wholeWeight(), pointWeight = kernel_.pointWeight(d);
  double f = 0;
  for (Eigen::Index i = 0; i < support_.rows(); ++i) {
    const double alpha = weights_[i];
    double whole = 0, points = 0;
    for (std::size_t c = 0; c < d; ++c) {
      diff[c] = x[c] - support_(i, static_cast<Eigen::Index>(c));
      whole += diff[c] * diff[c];
    }
    if (block == 0) {
      f += alpha * kernel_(whole);
      const double scale = 2 * alpha * kernel_.derivative(whole);
      for (std::size_t c = 0; c < d; ++c) dfdx[c] += scale * diff[c];
      continue;
    }
    for (std::size_t g = 0; g < d; g += block) {
      double r2 = 0;
      for (std::size_t c = g; c < g + block; ++c) r2 += diff[c] * diff[c];
      points += kernel_(r2);
      const double scale = 2 * alpha * pointWeight * kernel_.derivative(r2);
      for (std::size_t c = g; c < g + block; ++c) dfdx[c] += scale * diff[c];
    }
    f += alpha * (wholeWeight * kernel_(whole) + pointWeight * points);
    const double scale = 2 * alpha * wholeWeight * kernel_.derivative(whole);
    for (std::size_t c = 0; c < d; ++c) dfdx[c] += scale * diff[c];
  }
  ScoreGradient out{
      f, jacobian * Eigen::Map<const Eigen::VectorXd>(dfdx.data(), static_cast<Eigen::Index>(d))};
  return out;
}

Model::ScoreGradients Model::scoreGradients(const Configurations& q) const {
  features_.check(q);
  ScoreGradients out{Eigen::VectorXd(q.rows()), Configurations(q.rows(), q.cols())};
  std::vector<double> jacobian(featureDim() * dim());  // one buffer for every row
  for (Eigen::Index r = 0; r < q.rows(); ++r)
    out.scores[r] =
        scoreGradientInto(q.row(r).data(), jacobian.data(), out.gradients.row(r).data());
  return out;
}

}  // namespace fastron
