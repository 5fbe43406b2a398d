#include "fastron/baselines/box_qp.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <vector>

#include "fastron/core/error.h"

namespace fastron {
namespace {

double violationAt(double gradient, double x, double upper) {
  if (x <= 0) return std::max(-gradient, 0.0);
  if (x >= upper) return std::max(gradient, 0.0);
  return std::abs(gradient);
}

double violation(const Eigen::VectorXd& gradient, const Eigen::VectorXd& x, double upper) {
  double worst = 0;
  for (Eigen::Index i = 0; i < x.size(); ++i)
    worst = std::max(worst, violationAt(gradient[i], x[i], upper));
  return worst;
}

}  // namespace

double boxQpViolation(const Eigen::MatrixXd& B, const Eigen::VectorXd& c, double upper,
                      const Eigen::VectorXd& x) {
  return violation(B.transpose() * (B * x) - c, x, upper);
}

BoxQpResult solveBoxQp(const Eigen::MatrixXd& B, const Eigen::VectorXd& c, double upper,
                       double tolerance, std::size_t maxIterations, Eigen::VectorXd start) {
  const Eigen::Index n = c.size();
  if (B.cols() != n || start.size() != n) throw InvalidArgument("box QP: inconsistent sizes");
  if (!(upper > 0)) throw InvalidArgument("box QP: the upper bound must be positive");
  auto project = [upper](const Eigen::VectorXd& v) {
    return Eigen::VectorXd(v.cwiseMax(0.0).cwiseMin(upper));
  };
  auto objective = [&](const Eigen::VectorXd& x) { return 0.5 * (B * x).squaredNorm() - c.dot(x); };

  BoxQpResult result;
  result.x = project(start);
  const Eigen::VectorXd diagonal = B.colwise().squaredNorm().transpose();
  for (result.iterations = 0; result.iterations < maxIterations; ++result.iterations) {
    const Eigen::VectorXd g = B.transpose() * (B * result.x) - c;
    result.violation = violation(g, result.x, upper);
    if (result.violation <= tolerance) {
      result.converged = true;
      return result;
    }
    // Bounds within eps of binding whose gradient pushes outwards stay fixed (Bertsekas' eps-active
    // set, with eps the size of the projected-gradient step).
    const double eps =
        std::min(1e-3 * upper, (result.x - project(result.x - g)).cwiseAbs().maxCoeff());
    std::vector<Eigen::Index> free;
    for (Eigen::Index i = 0; i < n; ++i) {
      const bool atLower = result.x[i] <= eps && g[i] > 0;
      const bool atUpper = result.x[i] >= upper - eps && g[i] < 0;
      if (!atLower && !atUpper) free.push_back(i);
    }
    // Direction: Newton on the free variables, diagonally scaled gradient on the fixed ones.
    Eigen::VectorXd d(n);
    for (Eigen::Index i = 0; i < n; ++i) d[i] = -g[i] / std::max(diagonal[i], 1e-12);
    if (!free.empty()) {
      const auto f = static_cast<Eigen::Index>(free.size());
      Eigen::MatrixXd Bf(B.rows(), f);
      Eigen::VectorXd gf(f);
      for (Eigen::Index k = 0; k < f; ++k) {
        Bf.col(k) = B.col(free[static_cast<std::size_t>(k)]);
        gf[k] = g[free[static_cast<std::size_t>(k)]];
      }
      Eigen::MatrixXd Hf = Bf.transpose() * Bf;
      // A ridge relative to the diagonal keeps the factorisation defined where H_FF is singular.
      Hf.diagonal().array() += 1e-10 * (Hf.diagonal().maxCoeff() + 1e-300);
      const Eigen::VectorXd step = Hf.ldlt().solve(-gf);
      if (step.allFinite()) {
        for (Eigen::Index k = 0; k < f; ++k) d[free[static_cast<std::size_t>(k)]] = step[k];
      }
    }
    // Armijo search along the projection arc x(s) = P(x + s d).
    const double current = objective(result.x);
    bool accepted = false;
    for (double s = 1.0; s > 1e-12; s *= 0.5) {
      const Eigen::VectorXd candidate = project(result.x + s * d);
      const double predicted = g.dot(result.x - candidate);  // first-order decrease
      if (predicted > 0 && objective(candidate) <= current - 1e-4 * predicted) {
        result.x = candidate;
        accepted = true;
        break;
      }
    }
    if (!accepted) break;  // no further decrease is representable
  }
  result.violation = boxQpViolation(B, c, upper, result.x);
  result.converged = result.violation <= tolerance;
  return result;
}

}  // namespace fastron
