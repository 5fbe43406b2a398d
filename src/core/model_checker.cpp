#include "fastron/core/model_checker.h"

#include <algorithm>
#include <span>
#include <string>

#include "fastron/core/error.h"

namespace fastron {

ModelChecker::ModelChecker(std::shared_ptr<const Model> model, std::string name)
    : model_(std::move(model)), name_(std::move(name)) {
  if (!model_) throw InvalidArgument("ModelChecker: the model is a null pointer");
}

CombinedChecker::CombinedChecker(std::vector<std::shared_ptr<const CollisionChecker>> checkers,
                                 const char* kind, char separator)
    : checkers_(std::move(checkers)), separator_(separator) {
  if (checkers_.empty()) throw InvalidArgument(std::string(kind) + ": no checkers given");
  for (std::size_t i = 0; i < checkers_.size(); ++i) {
    if (!checkers_[i]) {
      throw InvalidArgument(std::string(kind) + ": checker " + std::to_string(i) +
                            " is a null pointer");
    }
    if (checkers_[i]->dof() != checkers_.front()->dof()) {
      throw InvalidArgument(std::string(kind) + ": '" + checkers_[i]->name() + "' has " +
                            std::to_string(checkers_[i]->dof()) + " dof, '" +
                            checkers_.front()->name() + "' " +
                            std::to_string(checkers_.front()->dof()));
    }
  }
}

std::string CombinedChecker::name() const {
  std::string joined;
  for (const auto& c : checkers_) {
    if (!joined.empty()) joined += separator_;
    joined += c->name();
  }
  return joined;
}

bool CombinedChecker::answersFromAModel() const {
  return std::any_of(checkers_.begin(), checkers_.end(),
                     [](const auto& c) { return c->answersFromAModel(); });
}

bool AnyOfChecker::check(const double* q) const {
  for (const auto& c : checkers()) {
    if (c->inCollision(std::span<const double>(q, dof()))) return true;
  }
  return false;
}

std::size_t AnyOfChecker::checkFirst(const double* q, std::size_t n) const {
  std::size_t first = n;
  for (const auto& c : checkers()) {
    if (first == 0) break;
    first = std::min(first, c->firstInCollision(q, first));
  }
  return first;
}

bool AllOfChecker::check(const double* q) const {
  for (const auto& c : checkers()) {
    if (!c->inCollision(std::span<const double>(q, dof()))) return false;
  }
  return true;
}

std::size_t AllOfChecker::checkFirst(const double* q, std::size_t n) const {
  const std::size_t d = dof();
  for (std::size_t begin = 0; begin < n;) {
    const std::size_t hit = begin + checkers().front()->firstInCollision(q + begin * d, n - begin);
    if (hit == n) return n;
    const bool confirmed = std::all_of(
        checkers().begin() + 1, checkers().end(),
        [&](const auto& c) { return c->inCollision(std::span<const double>(q + hit * d, d)); });
    if (confirmed) return hit;
    begin = hit + 1;
  }
  return n;
}

}  // namespace fastron
