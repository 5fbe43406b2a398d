#pragma once
// Central differences of a scalar function of a configuration: the reference for analytic
// gradients in tests.

#include <Eigen/Core>

namespace fastron::test {

/// (f(q + h e_j) - f(q - h e_j)) / 2h for every coordinate j; f takes a pointer to the values.
template <class F>
Eigen::VectorXd centralDifferences(const F& f, Eigen::VectorXd q, double h) {
  Eigen::VectorXd g(q.size());
  for (Eigen::Index j = 0; j < q.size(); ++j) {
    const double keep = q[j];
    q[j] = keep + h;
    const double plus = f(q.data());
    q[j] = keep - h;
    const double minus = f(q.data());
    q[j] = keep;
    g[j] = (plus - minus) / (2 * h);
  }
  return g;
}

}  // namespace fastron::test
