#include "fastron/core/hybrid_checker.h"

#include <algorithm>
#include <array>
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
  // Scored sixteen at a time (one pass of the batched features), so that an edge whose first
  // states already collide is not scored to its end. The states of a chunk inside the band, up to
  // the first the model alone calls colliding, go to the exact checker as one run in their order:
  // the same answer as asking them one by one, with one call's set-up (an FCL checker reads its
  // world and leases its scratch once per run).
  constexpr std::size_t kChunk = 16;
  std::array<double, kChunk> scores{};
  std::array<std::size_t, kChunk> asked{};  // the chunk's states inside the band, in order
  // Not thread_local: the exact checker may itself be a hybrid, calling this again on this thread
  // with these states (a vector per chunk costs nanoseconds beside an exact check).
  std::vector<double> askedStates;
  const std::size_t dim = dof();
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t count = std::min(kChunk, n - begin);
    const double* chunk = q + begin * dim;
    model_->scoreBatch(chunk, count, scores.data());
    std::size_t stop = count;  // the first state the model alone calls colliding
    std::size_t askedCount = 0;
    for (std::size_t k = 0; k < count && stop == count; ++k) {
      if (band_.contains(scores[k])) {
        asked[askedCount++] = k;
      } else if (scores[k] > band_.upper) {
        stop = k;
      }
    }
    std::size_t firstAsked = askedCount;  // the first asked state in collision
    if (askedCount > 0) {
      askedStates.resize(askedCount * dim);
      for (std::size_t a = 0; a < askedCount; ++a)
        std::copy_n(chunk + asked[a] * dim, dim, askedStates.begin() + a * dim);
      firstAsked = exact_->firstInCollision(askedStates.data(), askedCount);
    }
    if (firstAsked < askedCount) {
      // Answered: the states before it that the model decided, and the asked ones up to it.
      const std::size_t k = asked[firstAsked];
      modelAnswers_.fetch_add(k - firstAsked, std::memory_order_relaxed);
      exactAnswers_.fetch_add(firstAsked + 1, std::memory_order_relaxed);
      return begin + k;
    }
    exactAnswers_.fetch_add(askedCount, std::memory_order_relaxed);
    modelAnswers_.fetch_add(std::min(stop + 1, count) - askedCount, std::memory_order_relaxed);
    if (stop < count) return begin + stop;
  }
  return n;
}

}  // namespace fastron
