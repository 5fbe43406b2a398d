#include "fastron/core/hybrid_checker.h"

#include <string>
#include <vector>

#include "fastron/core/error.h"

namespace fastron {

HybridChecker::HybridChecker(std::shared_ptr<const Model> model,
                             std::shared_ptr<const CollisionChecker> exact, UncertaintyBand band)
    : model_(std::move(model)), exact_(std::move(exact)), band_(band) {
  if (!model_) throw InvalidArgument("HybridChecker: the model is a null pointer");
  if (!exact_) throw InvalidArgument("HybridChecker: the exact checker is a null pointer");
  if (exact_->dof() != model_->dim()) {
    throw InvalidArgument("HybridChecker: the model has " + std::to_string(model_->dim()) +
                          " joints but checker '" + exact_->name() + "' has " +
                          std::to_string(exact_->dof()));
  }
  if (!(band_.lower <= 0 && band_.upper >= 0)) {
    throw InvalidArgument("HybridChecker: the band [" + std::to_string(band_.lower) + ", " +
                          std::to_string(band_.upper) + "] does not contain the boundary 0");
  }
}

std::string HybridChecker::name() const {
  return "Fastron+" + exact_->name();
}

double HybridChecker::exactShare() const {
  const auto exact = static_cast<double>(exactAnswers());
  const double all = exact + static_cast<double>(modelAnswers());
  return all == 0 ? 0.0 : exact / all;
}

bool HybridChecker::decide(const double* q, double s) const {
  if (!band_.contains(s)) {
    modelAnswers_.fetch_add(1, std::memory_order_relaxed);
    return s > band_.upper;
  }
  exactAnswers_.fetch_add(1, std::memory_order_relaxed);
  return exact_->inCollision(std::span<const double>(q, dof()));
}

bool HybridChecker::check(const double* q) const {
  return decide(q, model_->score(q));
}

std::size_t HybridChecker::checkFirst(const double* q, std::size_t n) const {
  thread_local std::vector<double> scores;  // called per planner edge: no allocation
  scores.resize(n);
  model_->scoreBatch(q, n, scores.data());
  const std::size_t dim = dof();
  for (std::size_t i = 0; i < n; ++i) {
    if (decide(q + i * dim, scores[i])) return i;
  }
  return n;
}

}  // namespace fastron
