#include "fastron/core/reference_trainer.h"

#include <string>

#include "fastron/core/error.h"

namespace fastron {
namespace {

std::size_t misclassified(const std::vector<double>& f, const Labels& y) {
  std::size_t count = 0;
  for (std::size_t j = 0; j < f.size(); ++j) count += static_cast<double>(y[j]) * f[j] <= 0;
  return count;
}

}  // namespace

// Kept whole on purpose: the scalar baseline is Algorithm 1 as the paper writes it, one loop per
// line, so that the optimised Trainer::update is measured against the plainest reading.
ReferenceTraining trainReference(const Eigen::MatrixXd& x, const Labels& y,
                                 const TrainParams& params) {
  validate(params);
  const auto n = static_cast<std::size_t>(x.rows());
  const auto d = static_cast<std::size_t>(x.cols());
  validate(params.kernel, d);
  if (y.size() != n) {
    throw InvalidArgument("trainReference: " + std::to_string(n) + " points but " +
                          std::to_string(y.size()) + " labels");
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (y[j] != 1 && y[j] != -1) {
      throw InvalidArgument("trainReference: label [" + std::to_string(j) + "] must be +1 or -1");
    }
  }
  ReferenceTraining out;
  std::vector<double>& alpha = out.alpha;
  std::vector<double>& f = out.f;
  alpha.assign(n, 0.0);
  f.assign(n, 0.0);
  std::vector<double> column(n);
  const auto addColumn = [&](std::size_t i, double delta) {
    const auto xi = [&](std::size_t c) {
      return x(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c));
    };
    for (std::size_t j = 0; j < n; ++j) {
      const auto xj = [&](std::size_t c) {
        return x(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(c));
      };
      f[j] += delta * params.kernel.between<double>(xj, xi, d);
    }
  };
  const auto margin = [&](std::size_t j) { return static_cast<double>(y[j]) * f[j]; };

  UpdateReport& report = out.report;
  report.trainingPoints = n;
  std::size_t support = 0;
  std::vector<double> alphaBefore = alpha, fBefore = f;
  bool stopped = false;
  while (report.iterations < params.maxIterations && n > 0) {
    std::size_t i = 0;
    for (std::size_t j = 1; j < n; ++j) {
      if (margin(j) < margin(i)) i = j;
    }
    const double delta = (y[i] > 0 ? params.beta : -1.0) - f[i];
    if (margin(i) <= 0 && (support < params.maxSupportPoints || alpha[i] != 0) &&
        std::abs(alpha[i] + delta) <= params.maxWeightOverBeta * params.beta) {
      const bool wasSupport = alpha[i] != 0;
      addColumn(i, delta);
      alpha[i] += delta;
      support += static_cast<std::size_t>(!wasSupport && alpha[i] != 0);
      support -= static_cast<std::size_t>(wasSupport && alpha[i] == 0);
      ++report.iterations;
      continue;
    }
    alphaBefore = alpha;
    fBefore = f;
    std::size_t redundant = n;
    double best = 0;
    for (std::size_t s = 0; s < n; ++s) {
      if (alpha[s] == 0) continue;
      const double m = static_cast<double>(y[s]) * (f[s] - alpha[s]);
      if (m > best) {
        best = m;
        redundant = s;
      }
    }
    if (redundant < n) {
      addColumn(redundant, -alpha[redundant]);
      alpha[redundant] = 0;
      --support;
      ++report.iterations;
      continue;
    }
    report.stopReason = margin(i) > 0 ? StopReason::Converged
                        : alpha[i] == 0 && support >= params.maxSupportPoints
                            ? StopReason::SupportCap
                            : StopReason::WeightLimit;
    stopped = true;
    break;
  }
  if (!stopped && n > 0) report.stopReason = StopReason::IterationLimit;
  if (misclassified(fBefore, y) < misclassified(f, y)) {
    report.reverted = true;
    report.misclassifiedBeforeRevert = misclassified(f, y);
    alpha = alphaBefore;
    f = fBefore;
    support = 0;
    for (const double a : alpha) support += a != 0;
  }
  report.misclassified = misclassified(f, y);
  report.supportCount = support;
  report.gramColumnsComputed = report.iterations;
  return out;
}

}  // namespace fastron
