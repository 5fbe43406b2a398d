#pragma once
// The interface every exact collision checker (the oracle of the paper) implements, and an
// adapter for any callable. In core, so that the proxy pipeline needs no geometry library.

#include <atomic>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

/// Labels robot configurations (joint values) as in collision or free. Implementations must be
/// safe to call from many threads at once (per-thread scratch, const data), so labelling can run
/// on every core. Counts its calls.
class CollisionChecker {
 public:
  virtual ~CollisionChecker() = default;

  virtual std::string name() const = 0;
  /// Number of joint values in a configuration.
  virtual std::size_t dof() const = 0;

  /// True when q is in collision. Throws InvalidArgument on a wrong length or non-finite value.
  bool inCollision(std::span<const double> q) const;
  /// One result per row of q (1 = in collision), on the calling thread (inCollisionEach).
  /// Throws InvalidArgument when q does not have dof() columns or a row a non-finite value.
  std::vector<std::uint8_t> inCollisionBatch(const Configurations& q) const;
  /// out[i] = 1 when the i-th of n configurations (row by row in q, n * dof() values) is in
  /// collision, else 0. Counts n calls. Throws InvalidArgument naming the first row with a
  /// non-finite value.
  void inCollisionEach(const double* q, std::size_t n, std::uint8_t* out) const;
  /// Index of the first of n configurations (row by row in q, n * dof() values), in the order
  /// given, that is in collision, or n when all are free. Counts one call per configuration up to
  /// that one. Throws InvalidArgument naming the first row with a non-finite value.
  std::size_t firstInCollision(const double* q, std::size_t n) const;
  /// The same for every row of q; throws InvalidArgument when q does not have dof() columns.
  std::size_t firstInCollision(const Configurations& q) const;

  /// What a check of a motion found.
  struct MotionCheck {
    /// A state in collision, i in 1..segments (not necessarily the smallest), or 0 when none is.
    std::size_t collidingState = 0;
    std::size_t looked = 0;  ///< configurations looked at (the calls counted)
  };
  /// Looks at the straight motion from `from` to `to` (dof() values each) as a check at
  /// `segments` equal steps does: the states motionState(from, to, i, segments) for
  /// i = 1..segments (`to` itself last; `from` is not looked at). A checker that can prove states
  /// free without checking each (provesMotionsFree) looks at fewer; the answer is the same.
  /// Counts one call per configuration looked at. Throws InvalidArgument on a non-finite value.
  MotionCheck motionCollision(const double* from, const double* to, std::size_t segments) const;
  /// True when motionCollision skips states it proves free (FclChecker's clearance bounds), so
  /// that a caller should hand it whole motions rather than their states one by one: planners'
  /// edges and verification's alike. False (the default): it looks at every state.
  virtual bool provesMotionsFree() const { return false; }

  /// True when the answers come, at least in part, from a learned model (ModelChecker,
  /// HybridChecker, an AnyOfChecker holding one). Planners check such a source's edges at
  /// PlannerOptions::modelResolution, and an exact checker verifies its paths.
  virtual bool answersFromAModel() const { return false; }

  std::uint64_t callCount() const { return calls_.load(std::memory_order_relaxed); }
  void resetCallCount() { calls_.store(0, std::memory_order_relaxed); }

 protected:
  /// The check itself, for dof() finite values.
  virtual bool check(const double* q) const = 0;
  /// firstInCollision for n rows of finite values; by default check() on one row after the other.
  /// A checker that answers many configurations at once faster overrides it.
  virtual std::size_t checkFirst(const double* q, std::size_t n) const;
  /// inCollisionEach for n rows of finite values; by default check() on one row after the other.
  /// A checker with per-call overhead (a read of its world, a scratch lease) overrides it to pay
  /// that once per run: paid per row, two labelling threads contended for it and labelled no
  /// faster than one (docs/performance.md).
  virtual void checkEach(const double* q, std::size_t n, std::uint8_t* out) const;

  /// motionCollision for finite ends and segments >= 1; by default checkFirst on its states in
  /// bisection order (motionStates).
  virtual MotionCheck checkMotion(const double* from, const double* to, std::size_t segments) const;
  /// The default checkMotion, for an override that declines a motion (its proof does not hold
  /// there).
  MotionCheck checkMotionStateByState(const double* from, const double* to,
                                      std::size_t segments) const;

 private:
  /// Throws InvalidArgument when q does not have dof() columns.
  void checkColumns(const Configurations& q) const;
  /// Throws InvalidArgument naming the first of n rows with a non-finite value.
  void checkFinite(const double* q, std::size_t n) const;

  mutable std::atomic<std::uint64_t> calls_{0};
};

/// A CollisionChecker around a callable `bool(const double* q)`, e.g. an analytic oracle.
/// The callable must itself be safe to call concurrently.
class FunctionChecker final : public CollisionChecker {
 public:
  FunctionChecker(std::string name, std::size_t dof, std::function<bool(const double*)> fn);
  std::string name() const override { return name_; }
  std::size_t dof() const override { return dof_; }

 protected:
  bool check(const double* q) const override { return fn_(q); }

 private:
  std::string name_;
  std::size_t dof_;
  std::function<bool(const double*)> fn_;
};

}  // namespace fastron
