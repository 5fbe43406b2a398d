#include "fastron/baselines/sparse_svm.h"

#include <cmath>
#include <string>

#include "fastron/baselines/box_qp.h"
#include "fastron/core/error.h"

namespace fastron {
SsvmClassifier::SsvmClassifier(JointLimits limits, Kernel kernel, SparseSvmParams params)
    : limits_(std::move(limits)), kernel_(kernel), params_(params) {
  validate(kernel_);
  if (kernel_.block != 0) {
    throw InvalidArgument("SSVM: the kernel must be of one term (block 0), got block " +
                          std::to_string(kernel_.block));
  }
  if (!(params_.C > 0)) throw InvalidArgument("SSVM: C must be positive");
  model_.terms =
      jointSpaceModel(limits_, kernel_, Eigen::MatrixXd(0, limits_.dim()), Eigen::VectorXd(0));
}

// Algorithm 4. Row 0 of Kbar (and alpha) is the bias; rows 1..n the kernel basis functions.
void SsvmClassifier::train(const Configurations& q, std::span<const std::int8_t> labels) {
  const Eigen::Index n = q.rows();
  if (static_cast<std::size_t>(n) != labels.size())
    throw InvalidArgument("SSVM: one label per configuration");
  if (n == 0) throw InvalidArgument("SSVM: no training data");
  const Eigen::MatrixXd x = limits_.toInput(q);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) y[i] = labels[static_cast<std::size_t>(i)];

  // Kbar = [1 K]^T diag(y), (n + 1) x n.
  Eigen::MatrixXd kbar(n + 1, n);
  kbar.row(0) = y.transpose();
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = j; i < n; ++i) {
      const double kij = kernel_((x.row(i) - x.row(j)).squaredNorm());
      kbar(i + 1, j) = kij * y[j];
      kbar(j + 1, i) = kij * y[i];
    }
  }

  Eigen::VectorXd alpha = Eigen::VectorXd::Ones(n + 1);
  report_ = {};
  auto nonzeros = [](const Eigen::VectorXd& v) { return (v.array() != 0).count(); };
  bool shrinking = false;
  for (report_.iterations = 1; report_.iterations <= params_.maxIterations; ++report_.iterations) {
    // B = A Kbar over the rows with nonzero alpha (the others contribute nothing to H).
    std::vector<Eigen::Index> rows;
    for (Eigen::Index i = 0; i <= n; ++i) {
      if (alpha[i] != 0) rows.push_back(i);
    }
    Eigen::MatrixXd B(static_cast<Eigen::Index>(rows.size()), n);
    for (std::size_t r = 0; r < rows.size(); ++r)
      B.row(static_cast<Eigen::Index>(r)) = alpha[rows[r]] * kbar.row(rows[r]);
    const BoxQpResult qp = solveBoxQp(B, Eigen::VectorXd::Ones(n), params_.C, params_.qpTolerance);
    report_.qpIterations += qp.iterations;
    report_.qpConverged = report_.qpConverged && qp.converged;
    report_.qpStationarity = qp.stationarity;
    report_.qpComplementarity = qp.complementarity;
    if (!qp.converged) {
      // A QP answer that missed its tolerance would be amplified by the reweighting: keep the
      // weights of the last converged iteration and stop.
      report_.stoppedByQp = true;
      break;
    }
    const Eigen::VectorXd w = B * qp.x;

    const Eigen::VectorXd previous = alpha;
    alpha.setZero();  // alpha = A w on the rows that took part
    for (std::size_t r = 0; r < rows.size(); ++r)
      alpha[rows[r]] = previous[rows[r]] * w[static_cast<Eigen::Index>(r)];
    const double threshold = params_.zeroThreshold * alpha.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i <= n; ++i) {
      if (std::abs(alpha[i]) < threshold) alpha[i] = 0;
    }
    // Algorithm 4 stops when the model size stops changing. Taken literally it stops after the
    // first iteration, before the reweighting has set anything to zero (alpha starts at 1), so
    // the count is compared once it has started to fall; Huang et al.'s own rule (the weights
    // change by less than 1e-4) ends runs where it never falls.
    const auto count = nonzeros(alpha), before = nonzeros(previous);
    shrinking = shrinking || count < before;
    if (shrinking && count == before) break;
    if ((alpha - previous).norm() <= 1e-4 * alpha.norm()) break;
  }
  report_.iterations = std::min(report_.iterations, params_.maxIterations);

  std::vector<Eigen::Index> support;
  for (Eigen::Index i = 1; i <= n; ++i) {
    if (alpha[i] != 0) support.push_back(i);
  }
  Eigen::MatrixXd points(static_cast<Eigen::Index>(support.size()), x.cols());
  Eigen::VectorXd weights(static_cast<Eigen::Index>(support.size()));
  for (std::size_t k = 0; k < support.size(); ++k) {
    points.row(static_cast<Eigen::Index>(k)) = x.row(support[k] - 1);
    weights[static_cast<Eigen::Index>(k)] = alpha[support[k]];
  }
  model_ = {jointSpaceModel(limits_, kernel_, std::move(points), std::move(weights)), alpha[0]};
}

}  // namespace fastron
