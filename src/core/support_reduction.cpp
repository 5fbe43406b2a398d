#include "fastron/core/support_reduction.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "fastron/core/error.h"

namespace fastron {
namespace {

/// Support point indices ordered by |weight|, increasing or decreasing.
std::vector<Eigen::Index> byWeight(const Eigen::VectorXd& weights, bool increasing) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(weights.size()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return increasing ? std::abs(weights[a]) < std::abs(weights[b])
                      : std::abs(weights[a]) > std::abs(weights[b]);
  });
  return order;
}

/// `model` with only the support points `rows` (in the support set's order) and these weights.
std::shared_ptr<const Model> withSupport(const Model& model, std::vector<Eigen::Index> rows,
                                         const Eigen::VectorXd& weights) {
  std::sort(rows.begin(), rows.end());
  return std::make_shared<const Model>(
      model.features(), model.kernel(),
      Configurations(model.supportConfigurations()(rows, Eigen::all)),
      Eigen::VectorXd(weights(rows)));
}

}  // namespace

std::shared_ptr<const Model> pruneSupport(const Model& model, const Configurations& heldOut) {
  const Eigen::MatrixXd x = model.features().map(heldOut);  // checks columns and finiteness
  const Eigen::MatrixXd& support = model.supportFeatures();
  const Eigen::VectorXd& weights = model.weights();

  // Support point i's term at every held-out point, computed when needed (twice per point)
  // rather than kept: |S| x H of them would be hundreds of megabytes for large held-out sets.
  const auto d = static_cast<std::size_t>(x.cols());
  const auto termOf = [&](Eigen::Index i) -> Eigen::VectorXd {
    const auto s = [&](std::size_t c) { return support(i, static_cast<Eigen::Index>(c)); };
    Eigen::VectorXd term(x.rows());
    for (Eigen::Index j = 0; j < x.rows(); ++j) {
      const auto xj = [&](std::size_t c) { return x(j, static_cast<Eigen::Index>(c)); };
      term[j] = weights[i] * model.kernel().between<double>(s, xj, d);
    }
    return term;
  };
  Eigen::VectorXd f = Eigen::VectorXd::Zero(x.rows());
  for (Eigen::Index i = 0; i < support.rows(); ++i) f += termOf(i);
  const Eigen::Array<bool, Eigen::Dynamic, 1> answers = f.array() > 0;

  std::vector<Eigen::Index> kept;
  Eigen::VectorXd without(f.size());
  for (const Eigen::Index i : byWeight(weights, true)) {
    without = f - termOf(i);
    if (((without.array() > 0) == answers).all()) {
      f.swap(without);
    } else {
      kept.push_back(i);
    }
  }
  return withSupport(model, std::move(kept), weights);
}

std::shared_ptr<const Model> mergeSupport(const Model& model, double radius) {
  if (!(radius >= 0) || !std::isfinite(radius)) {
    throw InvalidArgument("merge radius must be finite and >= 0, got " + std::to_string(radius));
  }
  const Eigen::MatrixXd& support = model.supportFeatures();
  Eigen::VectorXd weights = model.weights();
  std::vector<Eigen::Index> kept;
  for (const Eigen::Index i : byWeight(model.weights(), false)) {
    const auto into = std::find_if(kept.begin(), kept.end(), [&](Eigen::Index k) {
      return (weights[k] > 0) == (weights[i] > 0) &&
             (support.row(k) - support.row(i)).squaredNorm() < radius * radius;
    });
    if (into == kept.end()) {
      kept.push_back(i);
    } else {
      weights[*into] += weights[i];
    }
  }
  return withSupport(model, std::move(kept), weights);
}

}  // namespace fastron
