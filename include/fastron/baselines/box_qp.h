#pragma once
// Box-constrained convex quadratic programs with a factored Hessian:
//   min 1/2 |B x|^2 - c^T x   subject to 0 <= x <= upper,   i.e. H = B^T B.
//
// Solved by projected Newton (Bertsekas, 1982): bounds whose gradient pushes outwards are held
// fixed, a Newton step is taken on the free variables (with H_FF = B_F^T B_F, factored by LDLT),
// and an Armijo line search runs along the projection of that step onto the box. Kernel matrices
// have fast-decaying spectra, which makes first-order methods (projected gradient, coordinate
// descent) crawl on SSVM's problems; the Newton step is indifferent to the conditioning and
// converges in a few dozen iterations. It stops when the largest violation of the KKT conditions
// (the projected gradient) is below the tolerance.

#include <Eigen/Core>
#include <cstddef>

namespace fastron {

struct BoxQpResult {
  Eigen::VectorXd x;
  std::size_t iterations = 0;
  double violation = 0;  ///< largest projected-gradient component at x
  bool converged = false;
};

BoxQpResult solveBoxQp(const Eigen::MatrixXd& B, const Eigen::VectorXd& c, double upper,
                       double tolerance, std::size_t maxIterations, Eigen::VectorXd start);

/// Largest violation of the KKT conditions at x: |g_i| inside the box, max(-g_i, 0) at 0 and
/// max(g_i, 0) at the upper bound, with g = B^T B x - c.
double boxQpViolation(const Eigen::MatrixXd& B, const Eigen::VectorXd& c, double upper,
                      const Eigen::VectorXd& x);

}  // namespace fastron
