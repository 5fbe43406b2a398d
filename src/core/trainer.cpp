#include "fastron/core/trainer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "fastron/core/error.h"

namespace fastron {
namespace {

void checkLabels(std::span<const std::int8_t> labels, const char* what) {
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] != 1 && labels[i] != -1) {
      throw InvalidArgument(std::string(what) + " label [" + std::to_string(i) +
                            "] must be +1 or -1, got " + std::to_string(labels[i]));
    }
  }
}

}  // namespace

void validate(const TrainParams& params) {
  validate(params.kernel);
  if (!std::isfinite(params.beta) || params.beta < 1) {
    throw InvalidArgument("beta (conditional bias) must be finite and >= 1, got " +
                          std::to_string(params.beta));
  }
  if (params.maxSupportPoints == 0) {
    throw InvalidArgument("maxSupportPoints must be at least 1");
  }
}

TrainParams defaultTrainParams(FeatureKind kind) {
  TrainParams params;
  if (kind == FeatureKind::Kinematic) {
    params.kernel = {KernelType::RationalQuadratic, 40};
    params.beta = 10;
  } else {
    params.kernel = {KernelType::RationalQuadratic, 5};
    params.beta = 500;
  }
  return params;
}

std::string_view toString(StopReason reason) {
  switch (reason) {
    case StopReason::Converged:
      return "converged";
    case StopReason::SupportCap:
      return "support cap";
    case StopReason::IterationLimit:
      return "iteration limit";
  }
  return "unknown";
}

Trainer::Trainer(FeatureMap features, TrainParams params)
    : features_(std::move(features)), params_(params) {
  validate(params_);
  if (dim() == 0 || dim() > kMaxDimension) {
    throw InvalidArgument("trainer dimension must be between 1 and " +
                          std::to_string(kMaxDimension) + ", got " + std::to_string(dim()));
  }
  q_.resize(0, static_cast<Eigen::Index>(dim()));
  x_.resize(0, static_cast<Eigen::Index>(features_.featureDim()));
}

Eigen::VectorXd Trainer::kernelColumn(Eigen::Index i, Eigen::Index fromRow) const {
  const Eigen::Index rows = x_.rows() - fromRow;
  Eigen::ArrayXd r2 = Eigen::ArrayXd::Zero(rows);
  for (Eigen::Index j = 0; j < x_.cols(); ++j) {
    r2 += (x_.col(j).tail(rows).array() - x_(i, j)).square();
  }
  const Kernel& k = params_.kernel;
  if (k.type == KernelType::RationalQuadratic) return (1.0 + 0.5 * k.gamma * r2).square().inverse();
  return (-k.gamma * r2).exp();
}

// computeGramMatrixColumn(i) of Algorithm 1: evaluated once, when first needed, then cached.
const Eigen::VectorXd& Trainer::gramColumn(Eigen::Index i) {
  int& slot = columnOf_[static_cast<std::size_t>(i)];
  if (slot < 0) {
    slot = static_cast<int>(columns_.size());
    columns_.push_back(kernelColumn(i, 0));
    ++columnsComputed_;
  }
  return columns_[static_cast<std::size_t>(slot)];
}

void Trainer::addPoints(const Configurations& q, std::span<const std::int8_t> labels) {
  if (static_cast<std::size_t>(q.rows()) != labels.size()) {
    throw InvalidArgument(std::to_string(q.rows()) + " configurations but " +
                          std::to_string(labels.size()) + " labels");
  }
  checkLabels(labels, "new point");
  const Eigen::MatrixXd input = features_.map(q);  // checks the column count and finiteness

  const Eigen::Index oldN = x_.rows();
  const Eigen::Index added = q.rows();
  q_.conservativeResize(oldN + added, Eigen::NoChange);
  q_.bottomRows(added) = q;
  x_.conservativeResize(oldN + added, Eigen::NoChange);
  x_.bottomRows(added) = input;
  y_.conservativeResize(oldN + added);
  for (Eigen::Index i = 0; i < added; ++i) y_[oldN + i] = labels[static_cast<std::size_t>(i)];
  alpha_.conservativeResize(oldN + added);
  alpha_.tail(added).setZero();
  columnOf_.resize(static_cast<std::size_t>(oldN + added), -1);

  // Fill the cached Gram columns for the new rows, then F of the new points from the weights.
  f_.conservativeResize(oldN + added);
  f_.tail(added).setZero();
  for (Eigen::Index i = 0; i < oldN; ++i) {
    const int slot = columnOf_[static_cast<std::size_t>(i)];
    if (slot < 0) continue;
    Eigen::VectorXd& column = columns_[static_cast<std::size_t>(slot)];
    column.conservativeResize(oldN + added);
    column.tail(added) = kernelColumn(i, oldN);
    if (alpha_[i] != 0) f_.tail(added) += alpha_[i] * column.tail(added);
  }
}

void Trainer::relabel(std::span<const std::int8_t> labels) {
  if (labels.size() != size()) {
    throw InvalidArgument("relabel: " + std::to_string(labels.size()) + " labels for " +
                          std::to_string(size()) + " training points");
  }
  checkLabels(labels, "relabelled point");
  for (Eigen::Index i = 0; i < y_.size(); ++i) {
    y_[i] = labels[static_cast<std::size_t>(i)];
    if (alpha_[i] != 0 && alpha_[i] * y_[i] < 0) {
      f_ -= alpha_[i] * gramColumn(i);
      alpha_[i] = 0;
      --supportCount_;
    }
  }
}

std::size_t Trainer::countMisclassified(const Eigen::VectorXd& f) const {
  return static_cast<std::size_t>((y_.array() * f.array() <= 0).count());
}

UpdateReport Trainer::update() {
  const auto start = std::chrono::steady_clock::now();
  UpdateReport report;
  report.trainingPoints = size();
  columnsComputed_ = 0;

  Eigen::VectorXd alphaBefore = alpha_;
  Eigen::VectorXd fBefore = f_;
  bool stopped = false;
  while (report.iterations < params_.maxIterations && y_.size() > 0) {
    // Check for misclassifications: the most negative margin y_i F_i (Eq. 17).
    Eigen::Index i = 0;
    const double worstMargin = (y_.array() * f_.array()).minCoeff(&i);
    if (worstMargin <= 0 && (supportCount_ < params_.maxSupportPoints || alpha_[i] != 0)) {
      // Add or adjust a support point: Delta alpha = beta^(0.5 (y_i + 1)) y_i - F_i (Eq. 18).
      const double target = y_[i] > 0 ? params_.beta : -1.0;
      const double delta = target - f_[i];
      const bool wasSupport = alpha_[i] != 0;
      f_ += delta * gramColumn(i);
      alpha_[i] += delta;
      supportCount_ += static_cast<std::size_t>(!wasSupport && alpha_[i] != 0);
      supportCount_ -= static_cast<std::size_t>(wasSupport && alpha_[i] == 0);
      ++report.iterations;
      continue;
    }

    alphaBefore = alpha_;
    fBefore = f_;
    // Remove the redundant support point whose margin without itself, y_i (F_i - alpha_i), is
    // the largest positive one.
    Eigen::Index redundant = -1;
    double bestMargin = 0;
    for (Eigen::Index s = 0; s < alpha_.size(); ++s) {
      if (alpha_[s] == 0) continue;
      const double margin = y_[s] * (f_[s] - alpha_[s]);
      if (margin > bestMargin) {
        bestMargin = margin;
        redundant = s;
      }
    }
    if (redundant >= 0) {
      f_ -= alpha_[redundant] * gramColumn(redundant);
      alpha_[redundant] = 0;
      --supportCount_;
      ++report.iterations;
      continue;
    }
    report.stopReason = worstMargin <= 0 ? StopReason::SupportCap : StopReason::Converged;
    stopped = true;
    break;
  }
  if (!stopped && y_.size() > 0) report.stopReason = StopReason::IterationLimit;

  // Revert the solution if the prior one was better (Algorithm 1, line 21).
  const std::size_t misclassifiedNow = countMisclassified(f_);
  const std::size_t misclassifiedBefore = countMisclassified(fBefore);
  if (misclassifiedBefore < misclassifiedNow) {
    alpha_ = alphaBefore;
    f_ = fBefore;
    supportCount_ = static_cast<std::size_t>((alpha_.array() != 0).count());
    report.reverted = true;
    report.misclassifiedBeforeRevert = misclassifiedNow;
  }
  report.misclassified = countMisclassified(f_);

  removeNonSupportPoints();
  report.supportCount = supportCount_;
  report.gramColumnsComputed = columnsComputed_;
  report.elapsed = std::chrono::steady_clock::now() - start;
  return report;
}

// removeNonsupportPoints() of Algorithm 1: every data structure shrinks to the support set, so
// a cached Gram column keeps only the rows of support points.
void Trainer::removeNonSupportPoints() {
  std::vector<Eigen::Index> keep;
  keep.reserve(supportCount_);
  for (Eigen::Index i = 0; i < alpha_.size(); ++i) {
    if (alpha_[i] != 0) keep.push_back(i);
  }
  if (keep.size() == static_cast<std::size_t>(alpha_.size())) return;

  const auto n = static_cast<Eigen::Index>(keep.size());
  Configurations q(n, q_.cols());
  Eigen::MatrixXd x(n, x_.cols());
  Eigen::VectorXd y(n), alpha(n), f(n);
  std::vector<Eigen::VectorXd> columns;
  std::vector<int> columnOf(keep.size(), -1);
  columns.reserve(keep.size());
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index i = keep[static_cast<std::size_t>(k)];
    q.row(k) = q_.row(i);
    x.row(k) = x_.row(i);
    y[k] = y_[i];
    alpha[k] = alpha_[i];
    f[k] = f_[i];
    const int slot = columnOf_[static_cast<std::size_t>(i)];
    if (slot >= 0) {
      const Eigen::VectorXd& old = columns_[static_cast<std::size_t>(slot)];
      Eigen::VectorXd column(n);
      for (Eigen::Index r = 0; r < n; ++r) column[r] = old[keep[static_cast<std::size_t>(r)]];
      columnOf[static_cast<std::size_t>(k)] = static_cast<int>(columns.size());
      columns.push_back(std::move(column));
    }
  }
  q_ = std::move(q);
  x_ = std::move(x);
  y_ = std::move(y);
  alpha_ = std::move(alpha);
  f_ = std::move(f);
  columns_ = std::move(columns);
  columnOf_ = std::move(columnOf);
}

std::shared_ptr<const Model> Trainer::model() const {
  std::vector<Eigen::Index> support;
  support.reserve(supportCount_);
  for (Eigen::Index i = 0; i < alpha_.size(); ++i) {
    if (alpha_[i] != 0) support.push_back(i);
  }
  // The private constructor: make_shared cannot reach it.
  return std::shared_ptr<const Model>(new Model(features_, params_.kernel, q_(support, Eigen::all),
                                                x_(support, Eigen::all), alpha_(support)));
}

}  // namespace fastron
