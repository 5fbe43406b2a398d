#pragma once
// A Fastron model answering as a CollisionChecker, and checkers combined: what a planner needs to
// plan on two models at once (e.g. a robot's self-collision model, learned once, beside a scene's
// obstacle model).

#include <memory>
#include <string>
#include <vector>

#include "fastron/core/collision_checker.h"
#include "fastron/core/export.h"
#include "fastron/core/model.h"

namespace FASTRON_API fastron {

/// The model's own answer (score > 0), one configuration at a time or a run of them as one batch
/// (Model::firstInCollision). Named `name`.
class ModelChecker final : public CollisionChecker {
 public:
  /// Throws InvalidArgument on a null model.
  ModelChecker(std::shared_ptr<const Model> model, std::string name = "Fastron");
  std::string name() const override { return name_; }
  std::size_t dof() const override { return model_->dim(); }
  const Model& model() const { return *model_; }
  bool answersFromAModel() const override { return true; }

 protected:
  bool check(const double* q) const override { return model_->inCollision(q); }
  std::size_t checkFirst(const double* q, std::size_t n) const override {
    return model_->firstInCollision(q, n);
  }

 private:
  std::shared_ptr<const Model> model_;
  std::string name_;
};

/// Several checkers of one robot answering as one: the common part of AnyOfChecker and
/// AllOfChecker (validation, name, dof, whether a model answers).
class CombinedChecker : public CollisionChecker {
 public:
  /// Its checkers' names joined by its separator ("+" for any of them, "&" for all).
  std::string name() const override;
  std::size_t dof() const override { return checkers_.front()->dof(); }
  /// True when one of its checkers answers from a model.
  bool answersFromAModel() const override;

 protected:
  /// Throws InvalidArgument, naming `kind`, on no checkers, a null one, or checkers of
  /// different dof.
  CombinedChecker(std::vector<std::shared_ptr<const CollisionChecker>> checkers, const char* kind,
                  char separator);
  const std::vector<std::shared_ptr<const CollisionChecker>>& checkers() const { return checkers_; }

 private:
  std::vector<std::shared_ptr<const CollisionChecker>> checkers_;
  char separator_;
};

/// In collision when any of its checkers says so. A run of configurations goes to each checker in
/// turn, the later ones only up to the first collision found so far. Named "a+b".
class AnyOfChecker final : public CombinedChecker {
 public:
  /// Throws InvalidArgument on no checkers, a null one, or checkers of different dof.
  explicit AnyOfChecker(std::vector<std::shared_ptr<const CollisionChecker>> checkers)
      : CombinedChecker(std::move(checkers), "AnyOfChecker", '+') {}

 protected:
  bool check(const double* q) const override;
  std::size_t checkFirst(const double* q, std::size_t n) const override;
};

/// In collision when every one of its checkers says so, asked in turn: a later checker only about
/// what every earlier one calls colliding. With a model first and an exact checker last, an
/// optimistic hybrid: the model's "free" is trusted and its "collides" confirmed, which reopens
/// what a conservative model closes. Named "a&b".
class AllOfChecker final : public CombinedChecker {
 public:
  /// Throws InvalidArgument on no checkers, a null one, or checkers of different dof.
  explicit AllOfChecker(std::vector<std::shared_ptr<const CollisionChecker>> checkers)
      : CombinedChecker(std::move(checkers), "AllOfChecker", '&') {}

 protected:
  bool check(const double* q) const override;
  /// A run goes to the first checker; each collision it finds is confirmed by the others, and
  /// the run goes on after one they call free.
  std::size_t checkFirst(const double* q, std::size_t n) const override;
};

}  // namespace fastron
