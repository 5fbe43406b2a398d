// Model::scoreGradient: f(q) and df/dq, for trajectory optimisation and repair (issue 53).
//
// f(q) = sum_i alpha_i k(x(q), s_i). With the one-term kernel k = k(|x - s|^2),
//   dk/dx = 2 k'(|x - s|^2) (x - s);
// with point terms k = W k(|x - s|^2) + P sum_g k(|x_g - s_g|^2),
//   dk/dx = 2 W k'(|x - s|^2) (x - s) + 2 P k'(|x_g - s_g|^2) (x_g - s_g) on each block g;
// and df/dq = J(q)^T df/dx, J the features' Jacobian (feature_map.h).

#include <algorithm>
#include <array>

#include "fastron/core/error.h"
#include "fastron/core/model.h"

namespace fastron {

namespace {

// Support points per pass: the padding of the query copies (kernel_sums.h), one fixed-size array
// that the compiler keeps in registers.
constexpr int kChunk = 16;
using Chunk = Eigen::Array<float, kChunk, 1>;

/// k and dk/dr2 of every term of a chunk of squared distances.
void termsOf(const Kernel& kernel, const Chunk& r2, Chunk& k, Chunk& derivative) {
  const auto gamma = static_cast<float>(kernel.gamma);
  if (kernel.type == KernelType::RationalQuadratic) {
    const Chunk inverse = (1.0F + (0.5F * gamma) * r2).inverse();
    k = inverse.square();
    derivative = -gamma * k * inverse;
  } else {
    k = (-gamma * r2).exp();
    derivative = -gamma * k;
  }
}

}  // namespace

Model::ScoreGradient Model::scoreGradient(std::span<const double> q) const {
  checkConfiguration(q, dim());
  const std::size_t d = featureDim(), n = dim();
  // NOLINTBEGIN(cppcoreguidelines-pro-type-member-init): filled before they are read
  std::array<double, kMaxFeatureDimension> x;
  std::array<float, kMaxFeatureDimension> xf;
  std::array<Chunk, kMaxFeatureDimension> groupDerivative, dfdx;  // dfdx: per lane, summed last
  // NOLINTEND(cppcoreguidelines-pro-type-member-init)
  Eigen::MatrixXd jacobian(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(d));
  features_.jacobian(q.data(), x.data(), jacobian.data());  // J^T, as in scoreGradientExact
  for (std::size_t c = 0; c < d; ++c) xf[c] = static_cast<float>(x[c]);
  std::fill_n(dfdx.begin(), d, Chunk::Zero());
  const std::size_t block = kernel_.block == 0 ? d : kernel_.block, groups = d / block;
  const auto wholeWeight = static_cast<float>(kernel_.wholeWeight());
  const auto pointWeight = static_cast<float>(kernel_.pointWeight(d));
  Chunk f = Chunk::Zero();
  for (std::size_t first = 0; first < paddedCount_; first += kChunk) {
    const auto column = [&](std::size_t c) {
      return Eigen::Map<const Chunk>(supportSoa_.data() + c * paddedCount_ + first);
    };
    const Eigen::Map<const Chunk> alpha(weightsF_.data() + first);
    Chunk whole = Chunk::Zero(), points = Chunk::Zero(), k, derivative;
    for (std::size_t g = 0; g < groups; ++g) {
      Chunk r2 = Chunk::Zero();
      for (std::size_t c = g * block; c < (g + 1) * block; ++c) r2 += (column(c) - xf[c]).square();
      whole += r2;
      if (kernel_.block == 0) break;
      termsOf(kernel_, r2, k, groupDerivative[g]);
      points += k;
    }
    termsOf(kernel_, whole, k, derivative);
    f += alpha * (wholeWeight * k + pointWeight * points);
    // d/dx_c of the chunk's terms: 2 alpha (W k'(whole) + P k'(its group)) (x_c - s_c).
    const Chunk wholeCoefficient = 2.0F * wholeWeight * alpha * derivative;
    for (std::size_t g = 0; g < groups; ++g) {
      const Chunk coefficient =
          kernel_.block == 0
              ? wholeCoefficient
              : Chunk(wholeCoefficient + 2.0F * pointWeight * alpha * groupDerivative[g]);
      for (std::size_t c = g * block; c < (g + 1) * block; ++c)
        dfdx[c] += coefficient * (xf[c] - column(c));
    }
  }
  Eigen::VectorXd dfdxDouble(static_cast<Eigen::Index>(d));
  for (std::size_t c = 0; c < d; ++c) dfdxDouble[static_cast<Eigen::Index>(c)] = dfdx[c].sum();
  return {static_cast<double>(f.sum()), jacobian * dfdxDouble};
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
  for (Eigen::Index r = 0; r < q.rows(); ++r) {
    const Eigen::VectorXd row = q.row(r);
    ScoreGradient one = scoreGradient({row.data(), dim()});
    out.scores[r] = one.score;
    out.gradients.row(r) = one.gradient.transpose();
  }
  return out;
}

}  // namespace fastron
