#pragma once
// OMPL adapters: a StateValidityChecker and a MotionValidator over an exact CollisionChecker or a
// Fastron model snapshot, on a joint-space RealVectorStateSpace bounded by the joint limits.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <variant>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include "fastron/core/collision_checker.h"
#include "fastron/core/export.h"
#include "fastron/core/joint_limits.h"
#include "fastron/core/model.h"
#include "fastron/planning/state_answers.h"

namespace FASTRON_API fastron {

/// What decides whether a configuration collides: an exact checker (FK + FCL or GJK), or a
/// snapshot of a Fastron model. A model snapshot never changes, so a planner sees one consistent
/// C-space even while a ProxyCollisionDetector publishes newer models.
using CollisionSource =
    std::variant<std::shared_ptr<const CollisionChecker>, std::shared_ptr<const Model>>;

/// The source's name for reports: the checker's name, or "Fastron".
std::string sourceName(const CollisionSource& source);
/// Its number of joints; throws InvalidArgument when the source is a null pointer.
std::size_t sourceDof(const CollisionSource& source);

/// Index of the first of n configurations of `dim` values (row by row in `states`) that the
/// source finds in collision, or n: one batch through Model::firstInCollision for a model,
/// CollisionChecker::firstInCollision for a checker (one configuration after the other for an
/// exact checker; one scored batch for a HybridChecker). The source must not be null.
std::size_t firstCollision(const CollisionSource& source, const double* states, std::size_t n,
                           std::size_t dim);

/// How much a collision source was asked: the configurations it answered (a batch counts its rows
/// up to and including the first collision, those it was asked) and the time its answers took.
struct SourceUse {
  std::uint64_t answered = 0;
  std::chrono::nanoseconds time{0};
};

/// A SourceUse that the adapters sharing it add to, from any thread. The time is read from the
/// clock once before and once after each question (a state, or an edge's batch: most of a
/// planner's questions): about 60 ns a question on a 2-core AMD EPYC (steady_clock::now() 31
/// ns), counted in it.
class SourceUseCounter {
 public:
  void add(std::uint64_t answered, std::chrono::nanoseconds time);
  SourceUse total() const;

 private:
  std::atomic<std::uint64_t> answered_{0};
  std::atomic<std::int64_t> nanoseconds_{0};
};
using SharedSourceUse = std::shared_ptr<SourceUseCounter>;

/// firstCollision, adding the rows the source answered (up to the first collision) and the time
/// it took to `use`.
std::size_t firstCollision(const CollisionSource& source, const double* states, std::size_t n,
                           std::size_t dim, SourceUseCounter& use);

/// A state is valid when the source says it is collision-free.
class CollisionValidityChecker final : public ompl::base::StateValidityChecker {
 public:
  /// `use` (made when null) counts the states asked and their time, e.g. shared with a motion
  /// validator.
  CollisionValidityChecker(const ompl::base::SpaceInformationPtr& si, CollisionSource source,
                           SharedSourceUse use = nullptr);
  bool isValid(const ompl::base::State* state) const override;
  const SharedSourceUse& use() const { return use_; }

 private:
  CollisionSource source_;
  SharedSourceUse use_;
};

/// Checks a straight-line motion at a fixed resolution (see motionStates): with a model, all the
/// states of the edge are evaluated as one batch that stops at the first predicted collision;
/// with a checker, through CollisionChecker::firstInCollision in the same order, or as one
/// motionCollision when the checker proves motions free (CollisionChecker::provesMotionsFree). It
/// remembers the
/// answers about motions' end states (StateAnswers) and does not ask the source about the same
/// end state twice: a planner's validator lives for one query, during which the source's answer
/// about a configuration does not change.
class ResolutionMotionValidator final : public ompl::base::MotionValidator {
 public:
  /// `use` as for CollisionValidityChecker.
  ResolutionMotionValidator(const ompl::base::SpaceInformationPtr& si, CollisionSource source,
                            double resolution, SharedSourceUse use = nullptr);
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  /// Also reports the last valid state before the first collision along the motion (in order
  /// from s1) and its fraction of the way.
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

 private:
  /// firstCollision on the source, counted.
  std::size_t ask(const double* states, std::size_t n, std::size_t dim) const;

  CollisionSource source_;
  double resolution_;
  SharedSourceUse use_;
  mutable StateAnswers ends_;
};

/// A SpaceInformation for planning in the joint space of `limits` with `source` as collision
/// checker and edges checked at `resolution` (joint units). Already set up. The state space
/// registers no projection (setting one up per query cost more than a whole Fastron plan): a
/// planner that needs one, such as KPIECE, needs `registerDefaultProjection` first. Make one per
/// query: its motion validator remembers its answers about motions' end states, so an exact
/// checker whose scene changes (setScene) needs a new SpaceInformation after each change. Throws
/// InvalidArgument when the source's dof differs from the limits' dimension.
ompl::base::SpaceInformationPtr makeSpaceInformation(const CollisionSource& source,
                                                     const JointLimits& limits, double resolution);

/// What the source of `si` (from makeSpaceInformation) has answered through its validity checker
/// and motion validator so far, and the time it took; nothing for another SpaceInformation.
SourceUse sourceUse(const ompl::base::SpaceInformationPtr& si);

}  // namespace fastron
