#include "fastron/core/trainer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "fastron/core/error.h"
#include "gram_columns.h"
#include "helper_thread.h"

namespace fastron {
namespace {

static_assert(detail::kMaxGramFeatures == kMaxFeatureDimension);

void checkLabels(std::span<const std::int8_t> labels, const char* what) {
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] != 1 && labels[i] != -1) {
      throw InvalidArgument(std::string(what) + " label [" + std::to_string(i) +
                            "] must be +1 or -1, got " + std::to_string(labels[i]));
    }
  }
}

// Training features are rounded to float once, when points are added (queries compute features in
// float too; a model rebuilt from its configurations rounds them alike), and kept twice: as
// doubles, and as floats for the Gram columns of many features, half the bytes streamed per
// column (gram_columns_impl.h). A float widens to double exactly, so either copy gives the same
// column.

// F is summed in double: it is compared against 0 (Claim 1) and the revert safeguard counts signs.
// Gram columns are double, or float where TrainParams::floatGramColumns applies (a
// rational-quadratic kernel: sixteen rows per AVX-512 register instead of eight). A float value
// lies within columnError_ of the exact kernel (floatColumnError in gram_columns.h derives the
// bound), so each update of F by delta times a column moves it at most |delta| columnError_ from K
// alpha; fError_ adds these up. Margins larger than fError_ have their exact sign; the few smaller
// ones are computed again exactly (settleSigns) before an update decides anything that must be
// exact: whether it converged (Claim 1: if a margin turns out not positive, the iterations go on),
// the revert safeguard's counts, the misclassified count. The choices in between (the most negative
// margin, the redundant point, delta) may differ from the double columns' where two margins are
// within the bound of each other: the guarantees are the same, the support set may differ in such a
// tie. Double columns, one pass per feature column over contiguous memory then the kernel, took 8.5
// us for 10000 x 7 on the project's machine, against 113-225 us for Eigen expressions that
// allocated a fresh column each time.

/// `kernel` as the per-path passes read it.
detail::GramKernel gramKernel(const Kernel& kernel, Eigen::Index features) {
  const auto d = static_cast<std::size_t>(features);
  return {kernel.type, kernel.gamma, kernel.block, kernel.wholeWeight(), kernel.pointWeight(d)};
}

/// k[j - from] = K(x_i, x_j) for the rows j in [from, to), on the active SIMD path
/// (gram_columns_impl.h), in float or double.
void gramColumn(const Eigen::MatrixXd& x, const Eigen::MatrixXf& xf, Eigen::Index i,
                std::size_t from, std::size_t to, const Kernel& kernel, bool inFloat, double* k) {
  const auto& passes = detail::activeGramPasses();
  const auto rows = static_cast<std::size_t>(x.rows()),
             features = static_cast<std::size_t>(x.cols());
  if (inFloat) {
    passes.columnInFloat(xf.data(), rows, features, static_cast<std::size_t>(i), from, to,
                         gramKernel(kernel, x.cols()), k);
  } else {
    passes.column(x.data(), xf.data(), rows, features, static_cast<std::size_t>(i), from, to,
                  gramKernel(kernel, x.cols()), k);
  }
}

// Algorithm 1 on two cores: an iteration's Gram column and F update split into two halves of
// the rows, one taken by the calling thread and one by the helper (helper_thread.h). Each row's
// values do not depend on the half it is in, and the halves' minima are combined in row order,
// so the weights are those of one thread, bit for bit. Below Trainer::rowsToShareUpdate() rows an
// iteration is too short to pay for the round trip between the cores (about 1 us on this
// project's machine).
constexpr std::size_t kChunks = 2;

/// f += delta K(x_i, .), the Gram column of point i written to `column`, then the most negative
/// margin y_j f_j (returned) and its index (the first one on ties, in `worst`); `shared` counts
/// the call when the helper took part.
double addColumnAndFindWorst(const Eigen::MatrixXd& x, const Eigen::MatrixXf& xf, Eigen::Index i,
                             const Kernel& kernel, bool inFloat, double delta, Eigen::VectorXd& f,
                             const Eigen::VectorXd& y, double* column,
                             detail::HelperSession& helper, Eigen::Index& worst,
                             std::size_t& shared) {
  const auto n = static_cast<std::size_t>(f.size());
  const std::size_t chunks = helper.helped() ? kChunks : 1;
  // Chunk bounds on whole registers of rows (16 floats).
  const std::size_t rowsPerChunk = ((n + chunks - 1) / chunks + 15) / 16 * 16;
  std::array<double, kChunks> lowest{};
  std::array<std::size_t, kChunks> at{};
  auto chunk = [&](std::size_t c) {
    const std::size_t from = std::min(n, c * rowsPerChunk), to = std::min(n, from + rowsPerChunk);
    if (from == to) {
      lowest[c] = std::numeric_limits<double>::infinity();
      return;
    }
    gramColumn(x, xf, i, from, to, kernel, inFloat, column + from);
    lowest[c] = detail::activeGramPasses().addAndFindWorst(f.data() + from, y.data() + from,
                                                           to - from, column + from, delta, &at[c]);
    at[c] += from;
  };
  shared += static_cast<std::size_t>(helper.run(chunks, chunk));
  std::size_t best = 0;
  for (std::size_t c = 1; c < chunks; ++c) {
    if (lowest[c] < lowest[best]) best = c;
  }
  worst = static_cast<Eigen::Index>(at[best]);
  return lowest[best];
}

/// The points of x with a nonzero weight side by side (row-major, for addSums), and their weights.
struct SupportRows {
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> points;
  Eigen::VectorXd weights;
};

SupportRows supportRows(const Eigen::MatrixXd& x, const Eigen::VectorXd& alpha, Eigen::Index n) {
  const auto count = static_cast<Eigen::Index>((alpha.head(n).array() != 0).count());
  SupportRows support{decltype(SupportRows::points)(count, x.cols()), Eigen::VectorXd(count)};
  for (Eigen::Index s = 0, k = 0; s < n; ++s) {
    if (alpha[s] == 0) continue;
    support.points.row(k) = x.row(s);
    support.weights[k++] = alpha[s];
  }
  return support;
}

}  // namespace

void validate(const TrainParams& params) {
  validate(params.kernel);
  if (!std::isfinite(params.beta) || params.beta < 1) {
    throw InvalidArgument("beta (conditional bias) must be finite and >= 1, got " +
                          std::to_string(params.beta));
  }
  if (!(params.maxWeightOverBeta >= 1)) {
    throw InvalidArgument("maxWeightOverBeta must be >= 1 (or infinity), got " +
                          std::to_string(params.maxWeightOverBeta));
  }
  if (params.maxSupportPoints == 0) {
    throw InvalidArgument("maxSupportPoints must be at least 1");
  }
}

TrainParams defaultTrainParams(FeatureKind kind, bool selfCollisionLabels) {
  TrainParams params;
  if (kind == FeatureKind::Kinematic && selfCollisionLabels) {
    params.kernel = {KernelType::RationalQuadratic, 40};
    params.beta = 10;
  } else if (kind == FeatureKind::Kinematic) {
    params.kernel = {KernelType::RationalQuadratic, 40, 3, 0.5};
    params.beta = 30;
  } else {
    params.kernel = {KernelType::RationalQuadratic, 5};
    params.beta = 500;
  }
  return params;
}

TrainParams sceneTrainParams(FeatureKind kind, bool selfCollisionLabels) {
  TrainParams params = defaultTrainParams(kind, selfCollisionLabels);
  params.maxIterations = 20000;
  params.maxSupportPoints = kRobotSupportCap;
  if (kind == FeatureKind::Kinematic && !selfCollisionLabels) {
    params.kernel = {KernelType::RationalQuadratic, 60, 3, 0};
    params.beta = 40;
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
    case StopReason::WeightLimit:
      return "weight limit";
  }
  return "unknown";
}

Trainer::Trainer(FeatureMap features, TrainParams params)
    : features_(std::move(features)), params_(params) {
  validate(params_);
  validate(params_.kernel, features_.featureDim());
  if (dim() == 0 || dim() > kMaxDimension) {
    throw InvalidArgument("trainer dimension must be between 1 and " +
                          std::to_string(kMaxDimension) + ", got " + std::to_string(dim()));
  }
  q_.resize(0, static_cast<Eigen::Index>(dim()));
  x_.resize(0, static_cast<Eigen::Index>(features_.featureDim()));
  if (params_.floatGramColumns && params_.kernel.type == KernelType::RationalQuadratic) {
    columnError_ =
        detail::floatColumnError(gramKernel(params_.kernel, x_.cols()), features_.featureDim());
  }
}

void Trainer::computeColumn(Eigen::Index i) {
  gramColumn(x_, xf_, i, 0, size(), params_.kernel, columnError_ > 0, column_.data());
  ++columnsComputed_;
}

void Trainer::addPoints(const Configurations& q, std::span<const std::int8_t> labels,
                        const ChunkRunner& run) {
  if (static_cast<std::size_t>(q.rows()) != labels.size()) {
    throw InvalidArgument(std::to_string(q.rows()) + " configurations but " +
                          std::to_string(labels.size()) + " labels");
  }
  checkLabels(labels, "new point");
  features_.check(q);
  const Eigen::Index added = q.rows();
  // Features and F of the new rows in chunks of a few registers: F of 256 rows over |S| 540 in
  // 12 features takes about 0.15 ms, far more than handing a chunk to another thread.
  const auto inChunks = [&](const std::function<void(std::size_t, std::size_t)>& body) {
    constexpr std::size_t kChunk = 256;
    if (run) {
      run(static_cast<std::size_t>(added), kChunk, body);
    } else {
      body(0, static_cast<std::size_t>(added));
    }
  };
  Eigen::MatrixXd input(added, static_cast<Eigen::Index>(features_.featureDim()));
  inChunks([&](std::size_t begin, std::size_t end) {
    features_.mapRows(q, static_cast<Eigen::Index>(begin), static_cast<Eigen::Index>(end), input);
  });
  if (input.size() > 0 && !(input.cwiseAbs().maxCoeff() <= kMaxFloatValue)) {
    throw InvalidArgument(
        "features of the new points must be at most 1e30 in magnitude (training "
        "and queries compute them in float)");
  }

  const Eigen::Index oldN = x_.rows();
  q_.conservativeResize(oldN + added, Eigen::NoChange);
  q_.bottomRows(added) = q;
  xf_.conservativeResize(oldN + added, input.cols());
  xf_.bottomRows(added) = input.cast<float>();
  x_.conservativeResize(oldN + added, Eigen::NoChange);
  x_.bottomRows(added) = xf_.bottomRows(added).cast<double>();
  y_.conservativeResize(oldN + added);
  for (Eigen::Index i = 0; i < added; ++i) y_[oldN + i] = labels[static_cast<std::size_t>(i)];
  alpha_.conservativeResize(oldN + added);
  alpha_.tail(added).setZero();
  column_.resize(static_cast<std::size_t>(oldN + added));

  // F of the new points from the current weights: the support points' features side by side,
  // one pass over them per register of new rows (gram_columns_impl.h, addSums).
  f_.conservativeResize(oldN + added);
  f_.tail(added).setZero();
  const SupportRows support = supportRows(x_, alpha_, oldN);
  if (support.weights.size() == 0) return;
  const detail::GramKernel kernel = gramKernel(params_.kernel, x_.cols());
  inChunks([&](std::size_t begin, std::size_t end) {
    const auto from = static_cast<std::size_t>(oldN) + begin;
    detail::activeGramPasses().addSums(
        support.points.data(), support.weights.data(),
        static_cast<std::size_t>(support.weights.size()), x_.data(),
        static_cast<std::size_t>(x_.rows()), static_cast<std::size_t>(x_.cols()), from,
        static_cast<std::size_t>(oldN) + end, kernel, f_.data() + from);
  });
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
      computeColumn(i);
      f_ -= alpha_[i] * column();
      fError_ += std::abs(alpha_[i]) * columnError_;
      alpha_[i] = 0;
      --supportCount_;
    }
  }
}

void Trainer::forgetWeights() {
  alpha_.setZero();
  f_.setZero();
  fError_ = 0;
  supportCount_ = 0;
}

std::size_t Trainer::countMisclassified(const Eigen::VectorXd& f) const {
  return static_cast<std::size_t>((y_.array() * f.array() <= 0).count());
}

std::size_t Trainer::rowsToShareUpdate(SimdPath path) {
  return path == SimdPath::Avx512 ? 4096 : 2048;
}

// One function, longer than the others: it is Algorithm 1 step by step (the comments name the
// paper's equations and lines), so that a reader can hold it beside the paper.
UpdateReport Trainer::update(unsigned threads) {
  const auto start = std::chrono::steady_clock::now();
  UpdateReport report;
  report.trainingPoints = size();
  columnsComputed_ = 0;

  Eigen::VectorXd alphaBefore = alpha_;
  Eigen::VectorXd fBefore = f_;
  double fErrorBefore = fError_;
  const Eigen::Index n = y_.size();
  // The most negative margin y_i F_i (Eq. 17), kept up to date by each F update.
  Eigen::Index i = 0;
  double worstMargin = n > 0 ? (y_.array() * f_.array()).minCoeff(&i) : 0;
  bool stopped = false;
  const double maxWeight = params_.maxWeightOverBeta * params_.beta;
  const bool inFloat = columnError_ > 0;
  detail::HelperSession helper(threads != 1 && static_cast<std::size_t>(n) >= rowsToShareUpdate());
  for (;;) {
    while (report.iterations < params_.maxIterations && n > 0) {
      // Add or adjust a support point: Delta alpha = beta^(0.5 (y_i + 1)) y_i - F_i (Eq. 18).
      const double delta = (y_[i] > 0 ? params_.beta : -1.0) - f_[i];
      if (worstMargin <= 0 && (supportCount_ < params_.maxSupportPoints || alpha_[i] != 0) &&
          std::abs(alpha_[i] + delta) <= maxWeight) {
        const bool wasSupport = alpha_[i] != 0;
        alpha_[i] += delta;
        supportCount_ += static_cast<std::size_t>(!wasSupport && alpha_[i] != 0);
        supportCount_ -= static_cast<std::size_t>(wasSupport && alpha_[i] == 0);
        worstMargin = addColumnAndFindWorst(x_, xf_, i, params_.kernel, inFloat, delta, f_, y_,
                                            column_.data(), helper, i, report.sharedIterations);
        fError_ += std::abs(delta) * columnError_;
        ++columnsComputed_;
        ++report.iterations;
        continue;
      }

      alphaBefore = alpha_;  // same sizes: no allocation
      fBefore = f_;
      fErrorBefore = fError_;
      // Remove the redundant support point whose margin without itself, y_i (F_i - alpha_i), is
      // the largest positive one.
      Eigen::Index redundant = -1;
      double bestMargin = 0;
      for (Eigen::Index s = 0; s < n; ++s) {
        if (alpha_[s] == 0) continue;
        const double margin = y_[s] * (f_[s] - alpha_[s]);
        if (margin > bestMargin) {
          bestMargin = margin;
          redundant = s;
        }
      }
      if (redundant >= 0) {
        worstMargin =
            addColumnAndFindWorst(x_, xf_, redundant, params_.kernel, inFloat, -alpha_[redundant],
                                  f_, y_, column_.data(), helper, i, report.sharedIterations);
        fError_ += std::abs(alpha_[redundant]) * columnError_;
        ++columnsComputed_;
        alpha_[redundant] = 0;
        --supportCount_;
        ++report.iterations;
        continue;
      }
      report.stopReason = worstMargin > 0 ? StopReason::Converged
                          : alpha_[i] == 0 && supportCount_ >= params_.maxSupportPoints
                              ? StopReason::SupportCap
                              : StopReason::WeightLimit;
      stopped = true;
      break;
    }
    if (!stopped && n > 0) report.stopReason = StopReason::IterationLimit;
    // With float columns, the margins within fError_ of 0 get their exact signs; a margin that
    // was taken for positive and is not means training has not converged yet.
    if (fError_ == 0 || n == 0) break;
    if (settleSigns(f_, alpha_, fError_)) fError_ = 0;
    worstMargin = (y_.array() * f_.array()).minCoeff(&i);
    if (!(stopped && report.stopReason == StopReason::Converged && worstMargin <= 0)) break;
    stopped = false;
  }

  // Revert the solution if the prior one was better (Algorithm 1, line 21), on exact signs.
  if (fErrorBefore > 0 && settleSigns(fBefore, alphaBefore, fErrorBefore)) fErrorBefore = 0;
  const std::size_t misclassifiedNow = countMisclassified(f_);
  const std::size_t misclassifiedBefore = countMisclassified(fBefore);
  if (misclassifiedBefore < misclassifiedNow) {
    alpha_ = alphaBefore;
    f_ = fBefore;
    fError_ = fErrorBefore;
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

bool Trainer::settleSigns(Eigen::VectorXd& f, const Eigen::VectorXd& alpha, double bound) const {
  // Beside the float columns' bound, the rounding of F's sums in double (far smaller).
  const double open = bound + 1e-9 * std::max(1.0, params_.beta);
  std::vector<Eigen::Index> rows;
  for (Eigen::Index j = 0; j < f.size(); ++j) {
    if (std::abs(f[j]) <= open) rows.push_back(j);
  }
  if (rows.empty()) return false;
  // Many open signs (a bound grown over long training): all of F again, which resets the bound.
  const bool all = rows.size() > static_cast<std::size_t>(f.size()) / 4;
  if (all) {
    rows.resize(static_cast<std::size_t>(f.size()));
    for (std::size_t j = 0; j < rows.size(); ++j) rows[j] = static_cast<Eigen::Index>(j);
  }
  const SupportRows support = supportRows(x_, alpha, alpha.size());
  const auto count = static_cast<Eigen::Index>(rows.size());
  const Eigen::MatrixXd points = x_(rows, Eigen::all);  // column-major, as addSums reads them
  Eigen::VectorXd exact = Eigen::VectorXd::Zero(count);
  if (support.weights.size() > 0) {
    detail::activeGramPasses().addSums(
        support.points.data(), support.weights.data(),
        static_cast<std::size_t>(support.weights.size()), points.data(),
        static_cast<std::size_t>(count), static_cast<std::size_t>(points.cols()), 0,
        static_cast<std::size_t>(count), gramKernel(params_.kernel, x_.cols()), exact.data());
  }
  f(rows) = exact;
  return all;
}

// removeNonsupportPoints() of Algorithm 1: every data structure shrinks to the support set.
void Trainer::removeNonSupportPoints() {
  std::vector<Eigen::Index> keep;
  keep.reserve(supportCount_);
  for (Eigen::Index i = 0; i < alpha_.size(); ++i) {
    if (alpha_[i] != 0) keep.push_back(i);
  }
  if (keep.size() == static_cast<std::size_t>(alpha_.size())) return;

  const auto n = static_cast<Eigen::Index>(keep.size());
  q_ = q_(keep, Eigen::all).eval();
  x_ = x_(keep, Eigen::all).eval();
  xf_ = xf_(keep, Eigen::all).eval();
  y_ = y_(keep).eval();
  alpha_ = alpha_(keep).eval();
  f_ = f_(keep).eval();
  column_.resize(static_cast<std::size_t>(n));
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
