#pragma once
// Sparse SVM (Huang et al. 2010) as the paper's Algorithm 4 states: an approximate L0 norm of the
// weights by an iteratively reweighted L2 norm.
//
// Each iteration solves the dual QP  min_b 1/2 b^T H b - 1^T b, 0 <= b <= C,  with
// H = Kbar^T A^2 Kbar = B^T B for B = A Kbar over the nonzero weights (solveBoxQp, an
// interior-point method), then sets alpha = A^2 Kbar b = A (B b).

#include "fastron/baselines/classifier.h"
#include "fastron/core/export.h"
#include "fastron/core/joint_limits.h"
#include "fastron/core/kernel.h"

namespace FASTRON_API fastron {

struct SparseSvmParams {
  double C = 10;
  double zeroThreshold = 1e-4;  ///< epsilon: |alpha_i| < epsilon * max|alpha| counts as 0
  std::size_t maxIterations = 30;
  double qpTolerance = 1e-6;  ///< KKT tolerance of each QP
};

struct SparseSvmReport {
  std::size_t iterations = 0, qpIterations = 0;
  bool qpConverged = true;  ///< every QP met its KKT tolerance
  /// A QP missed its tolerance; the weights are those of the last converged iteration (the
  /// interior-point solver loses accuracy late in runs with N in the thousands).
  bool stoppedByQp = false;
  double qpStationarity = 0, qpComplementarity = 0;  ///< of the last QP
};

class SsvmClassifier final : public Classifier {
 public:
  SsvmClassifier(JointLimits limits, Kernel kernel, SparseSvmParams params = {});
  std::string name() const override { return "SSVM"; }
  void train(const Configurations& q, std::span<const std::int8_t> labels) override;
  double score(const double* q) const override { return model_.score(q); }
  std::size_t supportCount() const override { return model_.supportCount(); }
  const SparseSvmReport& report() const { return report_; }
  const KernelExpansion& expansion() const { return model_; }
  const SparseSvmParams& params() const { return params_; }

 private:
  JointLimits limits_;
  Kernel kernel_;
  SparseSvmParams params_;
  KernelExpansion model_;
  SparseSvmReport report_;
};

}  // namespace fastron
