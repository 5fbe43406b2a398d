#pragma once
// Sparse SVM (Huang et al. 2010) as the paper's Algorithm 4 states: an approximate L0-norm of the
// weights by an iteratively reweighted L2 norm, each iteration solving the dual box-constrained
// QP (solveBoxQp), and stopping when the number of support points stops falling (see
// sparse_svm.cpp for how that rule is read).

#include "fastron/baselines/classifier.h"
#include "fastron/core/joint_limits.h"
#include "fastron/core/kernel.h"

namespace fastron {

struct SparseSvmParams {
  double C = 10;
  double zeroThreshold = 1e-4;  ///< epsilon: |alpha_i| < epsilon * max|alpha| counts as 0
  std::size_t maxIterations = 30;
  double qpTolerance = 1e-3;
  std::size_t qpMaxIterations = 500;
};

struct SparseSvmReport {
  std::size_t iterations = 0, qpIterations = 0;
  double qpViolation = 0;  ///< KKT violation of the last QP solution
  bool qpConverged = true;
};

class SsvmClassifier final : public Classifier {
 public:
  SsvmClassifier(JointLimits limits, Kernel kernel, SparseSvmParams params = {});
  std::string name() const override { return "SSVM"; }
  void train(const Configurations& q, std::span<const std::int8_t> labels) override;
  double score(const double* q) const override { return model_.score(q); }
  std::size_t supportCount() const override { return model_.supportCount(); }
  const SparseSvmReport& report() const { return report_; }

 private:
  JointLimits limits_;
  Kernel kernel_;
  SparseSvmParams params_;
  KernelExpansion model_;
  SparseSvmReport report_;
};

}  // namespace fastron
