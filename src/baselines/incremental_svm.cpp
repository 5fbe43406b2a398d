#include "fastron/baselines/incremental_svm.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"

namespace fastron {
namespace {

// Added to the kernel's diagonal: keeps the bordered margin matrix invertible when two margin
// vectors nearly coincide. Far below any tolerance the results are compared at.
constexpr double kRidge = 1e-9;
// Sensitivities smaller than this cannot bring a point to a set boundary.
constexpr double kTiny = 1e-12;

enum class Event {
  None,
  CandidateMargin,
  CandidateError,
  MarginToError,
  MarginToReserve,
  ToMargin
};

}  // namespace

IncrementalSvm::IncrementalSvm(Kernel kernel, double C) : kernel_(kernel), C_(C) {
  validate(kernel_);
  if (kernel_.block != 0) {
    throw InvalidArgument("ISVM: the kernel must be of one term (block 0), got block " +
                          std::to_string(kernel_.block));
  }
  if (!std::isfinite(C_) || C_ <= 0)
    throw InvalidArgument("SVM regularisation C must be finite and positive");
}

double IncrementalSvm::k(std::size_t i, std::size_t j) const {
  return kernel_((x_[i] - x_[j]).squaredNorm()) + (i == j ? kRidge : 0.0);
}

double IncrementalSvm::decision(const double* x) const {
  double f = b_;
  for (std::size_t i = 0; i < x_.size(); ++i) {
    if (alpha_[i] > 0) {
      f += alpha_[i] * y_[i] *
           kernel_((x_[i] - Eigen::Map<const Eigen::VectorXd>(x, x_[i].size())).squaredNorm());
    }
  }
  return f;
}

std::size_t IncrementalSvm::supportCount() const {
  return static_cast<std::size_t>(
      std::count_if(alpha_.begin(), alpha_.end(), [](double a) { return a > 0; }));
}

void IncrementalSvm::add(std::span<const double> x, std::int8_t label) {
  if (label != 1 && label != -1)
    throw InvalidArgument("SVM label must be +1 or -1, got " + std::to_string(label));
  if (!x_.empty() && x.size() != static_cast<std::size_t>(x_.front().size())) {
    throw InvalidArgument("SVM point has " + std::to_string(x.size()) + " values, expected " +
                          std::to_string(x_.front().size()));
  }
  for (const double v : x) {
    if (!std::isfinite(v)) throw InvalidArgument("SVM point has a non-finite value");
  }
  x_.emplace_back(Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size())));
  y_.push_back(label);
  alpha_.push_back(0);
  set_.push_back(Set::Reserve);
  g_.push_back(label * decision(x.data()) - 1);
  learn(x_.size() - 1);
}

// R computed afresh from the margin set: used when an incremental update would divide by a
// vanishing pivot (nearly dependent margin vectors).
void IncrementalSvm::rebuildR() {
  const auto m = static_cast<Eigen::Index>(margin_.size());
  Eigen::MatrixXd bordered(m + 1, m + 1);
  bordered(0, 0) = 0;
  for (Eigen::Index p = 0; p < m; ++p) {
    const std::size_t i = margin_[static_cast<std::size_t>(p)];
    bordered(0, p + 1) = bordered(p + 1, 0) = y_[i];
    for (Eigen::Index r = 0; r <= p; ++r) {
      bordered(r + 1, p + 1) = bordered(p + 1, r + 1) = q(margin_[static_cast<std::size_t>(r)], i);
    }
  }
  R_ = bordered.fullPivLu().inverse();
}

// Adds point i to the margin set S and grows R, the inverse of the bordered matrix
// [0 y_S^T; y_S Q_SS], by one row and column (Cauwenberghs and Poggio, Eq. 11).
void IncrementalSvm::joinMargin(std::size_t i) {
  set_[i] = Set::Margin;
  if (margin_.empty()) {
    R_.resize(2, 2);
    R_ << -q(i, i), y_[i], y_[i], 0;
    margin_.push_back(i);
    return;
  }
  const auto m = static_cast<Eigen::Index>(margin_.size());
  Eigen::VectorXd v(m + 1);
  v[0] = y_[i];
  for (Eigen::Index p = 0; p < m; ++p) v[p + 1] = q(margin_[static_cast<std::size_t>(p)], i);
  Eigen::VectorXd u(m + 2);
  u.head(m + 1) = -R_ * v;
  u[m + 1] = 1;
  const double gamma = q(i, i) + v.dot(u.head(m + 1));
  margin_.push_back(i);
  if (gamma < 1e-8 || !u.allFinite()) {
    rebuildR();
    return;
  }
  R_.conservativeResize(m + 2, m + 2);
  R_.row(m + 1).setZero();
  R_.col(m + 1).setZero();
  R_ += u * u.transpose() / gamma;
}

// Removes the margin vector at `position` and shrinks R (Cauwenberghs and Poggio, Eq. 12).
void IncrementalSvm::leaveMargin(std::size_t position) {
  margin_.erase(margin_.begin() + static_cast<std::ptrdiff_t>(position));
  if (margin_.empty()) {
    R_.resize(0, 0);
    return;
  }
  const auto k = static_cast<Eigen::Index>(position + 1);
  const Eigen::Index n = R_.rows();
  if (std::abs(R_(k, k)) < 1e-10 || !R_.allFinite()) {
    rebuildR();
    return;
  }
  const Eigen::MatrixXd updated = R_ - R_.col(k) * R_.row(k) / R_(k, k);
  Eigen::MatrixXd shrunk(n - 1, n - 1);
  for (Eigen::Index r = 0, rr = 0; r < n; ++r) {
    if (r == k) continue;
    for (Eigen::Index c = 0, cc = 0; c < n; ++c) {
      if (c == k) continue;
      shrunk(rr, cc++) = updated(r, c);
    }
    ++rr;
  }
  R_ = std::move(shrunk);
}

// Grows alpha_c from 0 in the largest steps that keep every other point's KKT conditions, until
// c itself reaches the margin (g_c = 0) or the bound C. Kept whole, as Cauwenberghs and Poggio's
// adiabatic increment reads: each step's bookkeeping (the sets, R, the step size) only makes
// sense beside the others.
void IncrementalSvm::learn(std::size_t c) {
  const std::size_t n = x_.size();
  if (g_[c] >= 0) return;  // already classified with margin: a reserve vector
  for (std::size_t round = 0; round < 50 + 20 * n; ++round) {
    if (margin_.empty()) {
      // No margin vectors: only the bias can move, dg_i = y_i db. Move it toward g_c = 0 until
      // the first point (c, or an error or reserve vector) reaches the margin.
      const double direction = y_[c];
      double t = -g_[c];
      std::size_t who = c;
      for (std::size_t i = 0; i < n; ++i) {
        if (i == c) continue;
        const double rate = y_[i] * direction;  // dg_i per unit t
        if (set_[i] == Set::Reserve && rate < 0 && g_[i] < t) {
          t = g_[i];
          who = i;
        } else if (set_[i] == Set::Error && rate > 0 && -g_[i] < t) {
          t = -g_[i];
          who = i;
        }
      }
      t = std::max(t, 0.0);
      b_ += direction * t;
      for (std::size_t i = 0; i < n; ++i) g_[i] += y_[i] * direction * t;
      g_[who] = 0;
      joinMargin(who);
      if (who == c) return;
      continue;
    }

    // Sensitivities: [db; dalpha_S] = beta dalpha_c, dg_i = gamma_i dalpha_c (Eq. 7-9).
    const auto m = static_cast<Eigen::Index>(margin_.size());
    Eigen::VectorXd v(m + 1);
    v[0] = y_[c];
    for (Eigen::Index p = 0; p < m; ++p) v[p + 1] = q(margin_[static_cast<std::size_t>(p)], c);
    const Eigen::VectorXd beta = -R_ * v;
    std::vector<double> gamma(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (set_[i] == Set::Margin) continue;
      double gi = q(i, c) + y_[i] * beta[0];
      for (Eigen::Index p = 0; p < m; ++p)
        gi += q(i, margin_[static_cast<std::size_t>(p)]) * beta[p + 1];
      gamma[i] = gi;
    }

    // The largest step before some point crosses a set boundary (bookkeeping, Sec. 3).
    double step = C_ - alpha_[c];
    Event event = Event::CandidateError;
    std::size_t who = c;
    auto consider = [&](double s, Event e, std::size_t i) {
      if (s < step) {
        step = s;
        event = e;
        who = i;
      }
    };
    if (gamma[c] > kTiny) consider(-g_[c] / gamma[c], Event::CandidateMargin, c);
    for (Eigen::Index p = 0; p < m; ++p) {
      const std::size_t j = margin_[static_cast<std::size_t>(p)];
      const double bj = beta[p + 1];
      if (bj > kTiny)
        consider((C_ - alpha_[j]) / bj, Event::MarginToError, static_cast<std::size_t>(p));
      if (bj < -kTiny)
        consider(-alpha_[j] / bj, Event::MarginToReserve, static_cast<std::size_t>(p));
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (i == c || set_[i] == Set::Margin) continue;
      if (set_[i] == Set::Error && gamma[i] > kTiny)
        consider(-g_[i] / gamma[i], Event::ToMargin, i);
      if (set_[i] == Set::Reserve && gamma[i] < -kTiny)
        consider(-g_[i] / gamma[i], Event::ToMargin, i);
    }
    step = std::max(step, 0.0);

    alpha_[c] += step;
    b_ += beta[0] * step;
    for (Eigen::Index p = 0; p < m; ++p) {
      const std::size_t j = margin_[static_cast<std::size_t>(p)];
      alpha_[j] = std::clamp(alpha_[j] + beta[p + 1] * step, 0.0, C_);
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (set_[i] != Set::Margin) g_[i] += gamma[i] * step;
    }
    if (!std::isfinite(b_) || !std::isfinite(alpha_[c])) {
      throw Error("incremental SVM: numerical breakdown while adding point " + std::to_string(c));
    }

    switch (event) {
      case Event::CandidateMargin:
        g_[c] = 0;
        joinMargin(c);
        return;
      case Event::CandidateError:
        alpha_[c] = C_;
        set_[c] = Set::Error;
        return;
      case Event::MarginToError:
      case Event::MarginToReserve: {
        const std::size_t j = margin_[who];
        alpha_[j] = event == Event::MarginToError ? C_ : 0.0;
        set_[j] = event == Event::MarginToError ? Set::Error : Set::Reserve;
        leaveMargin(who);
        break;
      }
      case Event::ToMargin:
        g_[who] = 0;
        joinMargin(who);
        break;
      case Event::None:
        break;
    }
  }
  throw Error("incremental SVM: no convergence while adding point " + std::to_string(c) +
              " (degenerate data?)");
}

double IncrementalSvm::maxKktViolation() const {
  double worst = 0, balance = 0;
  for (std::size_t i = 0; i < x_.size(); ++i) {
    const double g = y_[i] * decision(x_[i].data()) - 1;
    balance += alpha_[i] * y_[i];
    if (alpha_[i] < -1e-12 || alpha_[i] > C_ + 1e-12) worst = std::max(worst, 1.0);
    if (alpha_[i] <= 1e-12) {
      worst = std::max(worst, -g);  // reserve: g >= 0
    } else if (alpha_[i] >= C_ - 1e-12) {
      worst = std::max(worst, g);  // error: g <= 0
    } else {
      worst = std::max(worst, std::abs(g));  // margin: g = 0
    }
  }
  return std::max(worst, std::abs(balance));
}

KernelExpansion IncrementalSvm::expansion(const JointLimits& limits) const {
  const std::size_t count = supportCount();
  const auto d = static_cast<Eigen::Index>(limits.dim());
  Eigen::MatrixXd points(static_cast<Eigen::Index>(count), d);
  Eigen::VectorXd weights(static_cast<Eigen::Index>(count));
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < x_.size(); ++i) {
    if (!(alpha_[i] > 0)) continue;  // the same test as supportCount()
    points.row(row) = x_[i].transpose();
    weights[row++] = alpha_[i] * y_[i];
  }
  return {jointSpaceModel(limits, kernel_, std::move(points), std::move(weights)), b_};
}

// ---------------------------------------------------------------- Algorithm 3

IsvmClassifier::IsvmClassifier(JointLimits limits, Kernel kernel, IsvmActiveLearningParams params)
    : limits_(std::move(limits)), kernel_(kernel), params_(params), svm_(kernel, params.C) {
  model_ = svm_.expansion(limits_);
}

void IsvmClassifier::train(const Configurations& q, std::span<const std::int8_t> labels) {
  if (static_cast<std::size_t>(q.rows()) != labels.size())
    throw InvalidArgument("ISVM: one label per configuration");
  svm_ = IncrementalSvm(kernel_, params_.C);
  const Configurations x = limits_.toInput(q);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    svm_.add({x.row(i).data(), limits_.dim()}, labels[static_cast<std::size_t>(i)]);
  model_ = svm_.expansion(limits_);
}

namespace {

// argmax_x k(x, a) + k(x, b) for a radial kernel lies on the segment ab and, by symmetry, in
// its first half: golden-section search on t in [0, 1/2] of x = a + t (b - a).
Eigen::VectorXd pointBetween(const Kernel& kernel, const Eigen::VectorXd& a,
                             const Eigen::VectorXd& b) {
  const Eigen::VectorXd d = b - a;
  auto value = [&](double t) {
    return kernel((t * d).squaredNorm()) + kernel(((1 - t) * d).squaredNorm());
  };
  const double phi = (std::sqrt(5.0) - 1) / 2;
  double lo = 0, hi = 0.5;
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
  for (int i = 0; i < 40; ++i) {
    if (value(x1) > value(x2)) {
      hi = x2;
    } else {
      lo = x1;
    }
    x1 = hi - phi * (hi - lo);
    x2 = lo + phi * (hi - lo);
  }
  return a + 0.5 * (lo + hi) * d;
}

}  // namespace

std::size_t IsvmClassifier::trainActively(const Labeler& oracle) {
  const IsvmActiveLearningParams& p = params_;
  const auto d = static_cast<Eigen::Index>(limits_.dim());
  Rng rng(p.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), box(-1.0, 1.0);
  std::normal_distribution<double> jitter(0.0, 0.01 / std::sqrt(kernel_.gamma));
  svm_ = IncrementalSvm(kernel_, p.C);

  const Configurations initial = uniformConfigurations(limits_, p.initialPoints, rng);
  const Labels initialLabels = oracle(initial);
  std::size_t labelled = initial.rows();
  const Configurations initialInput = limits_.toInput(initial);
  for (Eigen::Index i = 0; i < initialInput.rows(); ++i) {
    svm_.add({initialInput.row(i).data(), limits_.dim()},
             initialLabels[static_cast<std::size_t>(i)]);
  }

  std::size_t added = 0;  // |X \ X_init|
  double explore = p.exploreProbability;
  while (added < p.maxAdded) {
    const auto n = static_cast<Eigen::Index>(std::min(p.batch, p.maxAdded - added));
    // Support vectors of each label, for exploitation.
    std::vector<Eigen::VectorXd> support;
    std::vector<double> supportLabel;
    for (std::size_t i = 0; i < svm_.size(); ++i) {
      if (svm_.alphas()[i] > 0) {
        support.push_back(svm_.point(i));
        supportLabel.push_back(svm_.label(i));
      }
    }
    const bool bothLabels =
        std::find(supportLabel.begin(), supportLabel.end(), 1.0) != supportLabel.end() &&
        std::find(supportLabel.begin(), supportLabel.end(), -1.0) != supportLabel.end();
    const bool exploring = unit(rng) < explore || !bothLabels;
    Configurations batch(n, d);
    for (Eigen::Index r = 0; r < n; ++r) {
      if (exploring) {
        for (Eigen::Index j = 0; j < d; ++j) batch(r, j) = box(rng);
        continue;
      }
      // Exploitation: between a random support vector and its nearest one of the other label.
      const std::size_t sel =
          std::uniform_int_distribution<std::size_t>(0, support.size() - 1)(rng);
      std::size_t nearest = sel;
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < support.size(); ++j) {
        const double dist = (support[j] - support[sel]).squaredNorm();
        if (supportLabel[j] != supportLabel[sel] && dist < best) {
          best = dist;
          nearest = j;
        }
      }
      // A small jitter (1% of the kernel width) keeps two draws of the same pair from adding the
      // same point twice, which would make the margin matrix singular.
      Eigen::VectorXd x = pointBetween(kernel_, support[sel], support[nearest]);
      for (auto& v : x) v = std::clamp(v + jitter(rng), -1.0, 1.0);
      batch.row(r) = x.transpose();
    }
    const Labels labels = oracle(limits_.toJoint(batch));
    labelled += static_cast<std::size_t>(n);

    std::size_t wrong = 0;
    for (Eigen::Index r = 0; r < n; ++r)
      wrong +=
          (svm_.decision(batch.row(r).data()) > 0) != (labels[static_cast<std::size_t>(r)] > 0);
    for (Eigen::Index r = 0; r < n; ++r)
      svm_.add({batch.row(r).data(), limits_.dim()}, labels[static_cast<std::size_t>(r)]);
    added += static_cast<std::size_t>(n);
    const double errorRate = static_cast<double>(wrong) / static_cast<double>(n);
    explore = std::clamp(
        explore + (exploring && errorRate > p.errorThreshold ? p.exploreStep : -p.exploreStep), 0.0,
        1.0);
    // Exit once the model classifies all new samples correctly. They are judged before they are
    // learned: after learning them the SVM fits them almost always, and the loop would stop
    // after its first batch instead of growing the set to N points as in the paper.
    if (wrong == 0) break;
  }
  model_ = svm_.expansion(limits_);
  return labelled;
}

}  // namespace fastron
