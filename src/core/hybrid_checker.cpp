#include "fastron/core/hybrid_checker.h"

#include <algorithm>
#include <array>
#include <string>

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
  // Scored sixteen at a time (one pass of the batched features), so that an edge whose first
  // states already collide is not scored to its end.
  constexpr std::size_t kChunk = 16;
  std::array<double, kChunk> scores{};
  const std::size_t dim = dof();
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t count = std::min(kChunk, n - begin);
    model_->scoreBatch(q + begin * dim, count, scores.data());
    for (std::size_t k = 0; k < count; ++k) {
      if (decide(q + (begin + k) * dim, scores[k])) return begin + k;
    }
  }
  return n;
}

}  // namespace fastron
