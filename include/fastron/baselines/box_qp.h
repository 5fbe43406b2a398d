#pragma once
// Box-constrained convex quadratic programs with a factored Hessian, the subproblem of SSVM:
//   min 1/2 |B x|^2 - c^T x   subject to 0 <= x <= upper   (H = B^T B).
//
// Solved by a primal-dual interior-point method (path following with a fixed centring parameter
// and a fraction-to-the-boundary step rule), as MATLAB's quadprog, which the paper used. Kernel
// matrices have fast-decaying spectra: first-order methods (projected gradient, coordinate
// descent, including LIBLINEAR's) stall on these problems, while each interior-point step solves
// the Newton system exactly: (B^T B + D) dx = r by the Woodbury identity with an m x m Cholesky
// factorisation when B has fewer rows m than columns n, else by an n x n one. It returns the dual
// variables of both bounds, so the KKT conditions can be checked directly.

#include <Eigen/Core>
#include <cstddef>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

struct BoxQpResult {
  Eigen::VectorXd x;
  Eigen::VectorXd lowerDual, upperDual;  ///< z >= 0 for x >= 0, w >= 0 for x <= upper
  std::size_t iterations = 0;
  double stationarity = 0;     ///< max |B^T B x - c - z + w|
  double complementarity = 0;  ///< max of x_i z_i and (upper - x_i) w_i
  bool converged = false;
};

/// Stops when stationarity and complementarity are both below `tolerance`.
BoxQpResult solveBoxQp(const Eigen::MatrixXd& B, const Eigen::VectorXd& c, double upper,
                       double tolerance, std::size_t maxIterations = 200);

}  // namespace fastron
