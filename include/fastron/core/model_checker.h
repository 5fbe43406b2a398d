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

/// In collision when any of its checkers says so. A run of configurations goes to each checker in
/// turn, the later ones only up to the first collision found so far.
class AnyOfChecker final : public CollisionChecker {
 public:
  /// Throws InvalidArgument on no checkers, a null one, or checkers of different dof.
  explicit AnyOfChecker(std::vector<std::shared_ptr<const CollisionChecker>> checkers);
  /// The names joined by "+".
  std::string name() const override;
  std::size_t dof() const override { return checkers_.front()->dof(); }
  /// True when one of its checkers answers from a model.
  bool answersFromAModel() const override;

 protected:
  bool check(const double* q) const override;
  std::size_t checkFirst(const double* q, std::size_t n) const override;

 private:
  std::vector<std::shared_ptr<const CollisionChecker>> checkers_;
};

}  // namespace fastron
