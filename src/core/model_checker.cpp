#include "fastron/core/model_checker.h"

#include <algorithm>
#include <span>

#include "fastron/core/error.h"

namespace fastron {

ModelChecker::ModelChecker(std::shared_ptr<const Model> model, std::string name)
    : model_(std::move(model)), name_(std::move(name)) {
  if (!model_) throw InvalidArgument("ModelChecker: the model is a null pointer");
}

AnyOfChecker::AnyOfChecker(std::vector<std::shared_ptr<const CollisionChecker>> checkers)
    : checkers_(std::move(checkers)) {
  if (checkers_.empty()) throw InvalidArgument("AnyOfChecker: no checkers given");
  for (std::size_t i = 0; i < checkers_.size(); ++i) {
    if (!checkers_[i]) {
      throw InvalidArgument("AnyOfChecker: checker " + std::to_string(i) + " is a null pointer");
    }
    if (checkers_[i]->dof() != checkers_.front()->dof()) {
      throw InvalidArgument("AnyOfChecker: '" + checkers_[i]->name() + "' has " +
                            std::to_string(checkers_[i]->dof()) + " dof, '" +
                            checkers_.front()->name() + "' " +
                            std::to_string(checkers_.front()->dof()));
    }
  }
}

std::string AnyOfChecker::name() const {
  std::string joined;
  for (const auto& c : checkers_) {
    if (!joined.empty()) joined += '+';
    joined += c->name();
  }
  return joined;
}

bool AnyOfChecker::answersFromAModel() const {
  return std::any_of(checkers_.begin(), checkers_.end(),
                     [](const auto& c) { return c->answersFromAModel(); });
}

bool AnyOfChecker::check(const double* q) const {
  for (const auto& c : checkers_) {
    if (c->inCollision(std::span<const double>(q, dof()))) return true;
  }
  return false;
}

std::size_t AnyOfChecker::checkFirst(const double* q, std::size_t n) const {
  std::size_t first = n;
  for (const auto& c : checkers_) {
    if (first == 0) break;
    first = std::min(first, c->firstInCollision(q, first));
  }
  return first;
}

}  // namespace fastron
