#pragma once
// Collision checkers that watch another's answers for one purpose: RecordingChecker keeps them
// (exact answers of verifying and repairing a plan become labelled configurations for the model's
// next update), CountedChecker counts them (the checks one plan asked of a shared checker).

#include <memory>
#include <mutex>
#include <vector>

#include "fastron/core/collision_checker.h"
#include "fastron/core/dataset.h"
#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// Answers with `inner` and records each configuration it was asked about with the answer (+1 in
/// collision, -1 free), in the order given. Safe to call from many threads (a mutex around the
/// record; the check itself runs outside it).
class RecordingChecker final : public CollisionChecker {
 public:
  /// Throws InvalidArgument on a null `inner`.
  explicit RecordingChecker(std::shared_ptr<const CollisionChecker> inner);

  std::string name() const override { return inner_->name(); }
  std::size_t dof() const override { return inner_->dof(); }
  bool provesMotionsFree() const override { return inner_->provesMotionsFree(); }

  /// Every answer recorded so far; the record is emptied.
  Dataset take();
  std::size_t recorded() const;

 protected:
  bool check(const double* q) const override;
  /// One call of inner's firstInCollision (so the inner checker's batch path is kept) and one
  /// record of every row it answered.
  std::size_t checkFirst(const double* q, std::size_t n) const override;
  /// One call of inner's inCollisionEach and one record of every row.
  void checkEach(const double* q, std::size_t n, std::uint8_t* out) const override;
  /// One call of inner's motionCollision; records the state in collision it found, if any, but
  /// not the states it looked at free (a checker that proves states free does not say which).
  MotionCheck checkMotion(const double* from, const double* to,
                          std::size_t segments) const override;

 private:
  /// Records the first n rows of q with their answers (1 in collision).
  void record(const double* q, std::size_t n, const auto& inCollision) const;

  std::shared_ptr<const CollisionChecker> inner_;
  mutable std::mutex mutex_;
  mutable std::vector<double> values_;  // dof() per answer
  mutable Labels labels_;
};

/// Answers with `inner` (its batch paths included) and counts, in its own callCount(), the
/// configurations asked through it: how many checks one use of a checker shared by others cost,
/// without keeping the answers. Safe to call from many threads.
class CountedChecker final : public CollisionChecker {
 public:
  /// Throws InvalidArgument on a null `inner`.
  explicit CountedChecker(std::shared_ptr<const CollisionChecker> inner);
  std::string name() const override { return inner_->name(); }
  std::size_t dof() const override { return inner_->dof(); }
  bool answersFromAModel() const override { return inner_->answersFromAModel(); }
  bool provesMotionsFree() const override { return inner_->provesMotionsFree(); }

 protected:
  bool check(const double* q) const override;
  std::size_t checkFirst(const double* q, std::size_t n) const override;
  void checkEach(const double* q, std::size_t n, std::uint8_t* out) const override;
  MotionCheck checkMotion(const double* from, const double* to,
                          std::size_t segments) const override;

 private:
  std::shared_ptr<const CollisionChecker> inner_;
};

}  // namespace fastron
