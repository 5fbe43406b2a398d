#include "fastron/baselines/box_qp.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "fastron/core/error.h"

namespace fastron {
namespace {

// Largest step in (0, 1] keeping v + s dv > 0, shortened to 99% of the way to the boundary.
double stepToBoundary(const Eigen::VectorXd& v, const Eigen::VectorXd& dv) {
  double step = 1.0;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (dv[i] < 0) step = std::min(step, -0.99 * v[i] / dv[i]);
  }
  return step;
}

}  // namespace

BoxQpResult solveBoxQp(const Eigen::MatrixXd& B, const Eigen::VectorXd& c, double upper,
                       double tolerance, std::size_t maxIterations) {
  const Eigen::Index n = c.size(), m = B.rows();
  if (B.cols() != n)
    throw InvalidArgument("box QP: B has " + std::to_string(B.cols()) + " columns for " +
                          std::to_string(n) + " variables");
  if (!(upper > 0) || !std::isfinite(upper))
    throw InvalidArgument("box QP: the upper bound must be positive");
  const bool woodbury = m < n;
  const Eigen::MatrixXd H = woodbury ? Eigen::MatrixXd() : Eigen::MatrixXd(B.transpose() * B);

  BoxQpResult r;
  Eigen::VectorXd x = Eigen::VectorXd::Constant(n, upper / 2);
  Eigen::VectorXd z = Eigen::VectorXd::Ones(n), w = Eigen::VectorXd::Ones(n);
  constexpr double kCentring = 0.1;
  for (r.iterations = 0; r.iterations < maxIterations; ++r.iterations) {
    const Eigen::VectorXd s = Eigen::VectorXd::Constant(n, upper) - x;
    const Eigen::VectorXd gradient = B.transpose() * (B * x) - c;
    const Eigen::VectorXd residual = gradient - z + w;
    r.stationarity = residual.cwiseAbs().maxCoeff();
    r.complementarity = std::max(x.cwiseProduct(z).maxCoeff(), s.cwiseProduct(w).maxCoeff());
    if (r.stationarity <= tolerance && r.complementarity <= tolerance) {
      r.converged = true;
      break;
    }
    const double mu = (x.dot(z) + s.dot(w)) / static_cast<double>(2 * n);
    const double target = kCentring * mu;
    // (H + D) dx = rhs, with D = Z/X + W/S from eliminating dz and dw.
    const Eigen::VectorXd d = z.cwiseQuotient(x) + w.cwiseQuotient(s);
    const Eigen::VectorXd rhs = -residual + (target / x.array() - z.array()).matrix() -
                                (target / s.array() - w.array()).matrix();
    Eigen::VectorXd dx;
    if (woodbury) {
      // (D + B^T B)^-1 = D^-1 - D^-1 B^T (I + B D^-1 B^T)^-1 B D^-1
      const Eigen::VectorXd dinv = d.cwiseInverse();
      const Eigen::MatrixXd scaled = B * dinv.asDiagonal();
      Eigen::MatrixXd small = scaled * B.transpose();
      small.diagonal().array() += 1.0;
      const Eigen::VectorXd t = dinv.cwiseProduct(rhs);
      dx = t - dinv.cwiseProduct(B.transpose() * small.llt().solve(B * t));
    } else {
      // H squares the kernel's condition number; LDLT with a ridge at rounding level stays
      // defined where a plain Cholesky factorisation breaks down near the solution.
      Eigen::MatrixXd system = H;
      system.diagonal() += d;
      system.diagonal().array() += 1e-14 * system.diagonal().maxCoeff();
      dx = system.ldlt().solve(rhs);
    }
    const Eigen::VectorXd dz = ((target - (x.cwiseProduct(z)).array()) / x.array()).matrix() -
                               z.cwiseQuotient(x).cwiseProduct(dx);
    const Eigen::VectorXd dw = ((target - (s.cwiseProduct(w)).array()) / s.array()).matrix() +
                               w.cwiseQuotient(s).cwiseProduct(dx);
    const double step = std::min({stepToBoundary(x, dx), stepToBoundary(s, -dx),
                                  stepToBoundary(z, dz), stepToBoundary(w, dw)});
    if (!(step > 0) || !dx.allFinite()) break;
    x += step * dx;
    z += step * dz;
    w += step * dw;
  }
  r.x = std::move(x);
  r.lowerDual = std::move(z);
  r.upperDual = std::move(w);
  return r;
}

}  // namespace fastron
