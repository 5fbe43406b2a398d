#pragma once
// Verify and repair (paper, Sec. IV-C "Performance in Motion Planning Application"): a plan made
// with an approximate checker (Fastron, GJK) is checked with the exact one, and every stretch
// that collides is cut out and replanned on the exact checker.

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fastron/core/dataset.h"
#include "fastron/core/export.h"
#include "fastron/planning/planner.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace FASTRON_API fastron {

/// One plan made before verification: on a model, on its hybrid, or on the exact checker for the
/// whole motion (repairs' bridges are not attempts: they are in repairTime).
struct PlanAttempt {
  std::string source;    ///< sourceName: "Fastron", "Fastron+FCL", "FCL", ...
  bool onModel = false;  ///< the source was a bare model (every check a model query)
  PlanStatus status = PlanStatus::Timeout;
  std::chrono::nanoseconds time{0};          ///< simplification included
  std::chrono::nanoseconds simplifyTime{0};  ///< of which shortening the path
  std::uint64_t checks = 0;                  ///< PlanResult::checks
  std::chrono::nanoseconds checkTime{0};     ///< PlanResult::checkTime: of `time`, answering them
  /// It planned between substitute ends (VerifiedPlan::substituteEnds).
  bool substituteEnds = false;
};

/// A plan made with an approximate checker, after verify and repair.
struct VerifiedPlan {
  PlanStatus status =
      PlanStatus::Timeout;  ///< Solved only when `path` is valid under the exact checker
  JointPath path;
  std::chrono::nanoseconds planTime{0};      ///< the approximate checker's plan, simplified
  std::chrono::nanoseconds simplifyTime{0};  ///< of which shortening the path
  /// of planTime: the model learning from verification between its plans (planVerifiedLearning)
  std::chrono::nanoseconds learnTime{0};
  std::chrono::nanoseconds verifyTime{0};  ///< exact checks of the plan, and of the repaired path
  std::chrono::nanoseconds repairTime{0};  ///< replanning of the invalid stretches
  std::size_t invalidStretches = 0;        ///< stretches cut out and replanned
  /// of invalidStretches: those that gradient repair (options.verify.gradientRepair) freed
  /// without replanning
  std::size_t gradientRepairs = 0;
  /// planVerifiedLearning: plans on the model that verification found colliding, after each of
  /// which the model learned and planned again
  std::size_t relearned = 0;
  /// The whole motion was planned on the exact checker: the approximate plan failed, or one of
  /// its stretches could not be bridged.
  bool wholePathReplanned = false;
  /// The approximate checker thought the start or goal collided while the exact one found them
  /// free: it planned between free configurations near them that the exact checker reaches from
  /// the true ends in a straight line.
  bool substituteEnds = false;
  std::string failure;  ///< why no valid path was found (empty when solved)
  /// The name of the source whose plan was verified (sourceName: "Fastron", the hybrid's
  /// "Fastron+FCL", ...), or the exact checker's when the whole motion was planned on it.
  std::string plannedOn;
  /// planVerified: every answer the exact checker gave (verification, repair, the ends), one row
  /// per call, label +1 in collision / -1 free: labelled configurations where the planner needed
  /// them, for the model's next update (ProxyCollisionDetector::addObservations).
  Dataset exactAnswers;
  /// Where the planning time went: every plan before verification, in order (planTime is their
  /// sum, with learnTime).
  std::vector<PlanAttempt> attempts;
  /// Configurations the exact checker answered for this plan: planning on it or on a hybrid,
  /// verification, repair, the ends.
  std::uint64_t exactChecks = 0;
  /// planVerifiedLearning with options.verify.oracleRelaxesExact: configurations its proxy's oracle
  /// answered in place of the exact checker (the optimistic hybrid's, the first repair round's).
  std::uint64_t relaxedChecks = 0;
  bool solved() const { return status == PlanStatus::Solved; }
  std::chrono::nanoseconds totalTime() const { return planTime + verifyTime + repairTime; }
};

/// Checks `path` (start to goal) with `exact` at options.resolution (checkPathParallel: every
/// core, bisection order); cuts out each invalid stretch (from the last free state before its
/// first collision to the first free state after its last one, walking the edges at
/// options.resolution), bridges it with the same planner on `exact` within the box those two
/// states span grown by options.verify.bridgeMargin, then within the joint limits (stretchShare
/// of the time limit each; when both fail, the whole motion with the full time limit), splices the
/// pieces and checks the whole path again (up to three rounds). planTime is left 0.
VerifiedPlan verifyAndRepair(const JointPath& path,
                             const std::shared_ptr<const CollisionChecker>& exact,
                             const JointLimits& limits, const PlannerOptions& options);

/// Plans with `approximate` (e.g. a Fastron model) for at most options.verify.approximateShare of
/// the time limit, then verifies and repairs with `exact`. When the approximate checker thinks the
/// start or goal collides but the exact one finds both free, it plans between configurations near
/// them that the approximate checker finds free and the exact one reaches from the true ends in a
/// straight line (`substituteEnds`), for at most options.verify.substituteShare of the time limit.
/// When the approximate plan fails, the whole motion is planned on the exact checker and counted as
/// repair. Start and goal must be free under `exact`, else the result is InvalidStart /
/// InvalidGoal. Every exact answer is returned in `exactAnswers`.
VerifiedPlan planVerified(const CollisionSource& approximate,
                          const std::shared_ptr<const CollisionChecker>& exact,
                          const JointLimits& limits, const Eigen::VectorXd& start,
                          const Eigen::VectorXd& goal, const PlannerOptions& options);

/// As planVerified above, but when `approximate` finds no path (a conservative model closes the
/// way near an end or a wall), an optimistic hybrid plans before `exact` does: an AllOfChecker of
/// `approximate` and `exact` (its "free" trusted, its "collides" confirmed), for another
/// approximateShare. The hybrid's questions go through the same record as verification's, so
/// `exactAnswers` and `exactChecks` hold them too. Throws InvalidArgument on a null `approximate`.
VerifiedPlan planVerifiedOptimistically(const std::shared_ptr<const CollisionChecker>& approximate,
                                        const std::shared_ptr<const CollisionChecker>& exact,
                                        const JointLimits& limits, const Eigen::VectorXd& start,
                                        const Eigen::VectorXd& goal, const PlannerOptions& options);

/// No hopeless waits on a model that closes a passage: plans on the model for
/// options.verify.approximateShare of the time limit; when that finds no path, on a HybridChecker
/// of the model and `exact` inside the calibrated band (which reopens what the model closed with
/// little confidence) for another approximateShare; only then on `exact` for the whole limit. The
/// hybrid step is skipped when the band was never calibrated. Otherwise as planVerified above; the
/// hybrid's exact answers are in `exactAnswers` too. Throws InvalidArgument on a null model.
VerifiedPlan planVerified(const CalibratedModel& model,
                          const std::shared_ptr<const CollisionChecker>& exact,
                          const JointLimits& limits, const Eigen::VectorXd& start,
                          const Eigen::VectorXd& goal, const PlannerOptions& options);

/// For a scene that stands still: plans on `proxy`'s latest model as planVerified above, but when
/// verification finds the model's path colliding, the model first learns the exact answers it
/// got wrong (answersMissedBy, addObservations, learnObservations: no oracle call) and plans again
/// on the new model, up to options.verify.learningRounds times; the last path is repaired as above.
/// The first plan on the model gets options.verify.modelShare of the time limit. When it fails, a
/// HybridChecker that trusts the model's "free" and asks `exact` (the proxy's oracle with
/// options.verify.oracleRelaxesExact) about every "collides" plans for approximateShare (the model
/// closes passages near walls where the robot is free; a calibrated band does not reach that far,
/// docs/planning.md), its path verified and repaired (the first round's bridges planned on the
/// oracle with options.verify.oracleRelaxesExact, except a stretch whose first collision the oracle
/// finds free); only then does `exact` plan the whole motion. A plan on a corrected model gets at
/// most four times the first plan's time (at least 50 ms, at most approximateShare) and, when it
/// fails, the last path is repaired. The proxy keeps what it learned for later queries; every exact
/// answer of every round is in `exactAnswers` (the oracle's answers are not).
/// Not while the proxy updates in the background: what it learns must be of the world as it is.
/// Throws Error before proxy.initialize().
VerifiedPlan planVerifiedLearning(ProxyCollisionDetector& proxy,
                                  const std::shared_ptr<const CollisionChecker>& exact,
                                  const JointLimits& limits, const Eigen::VectorXd& start,
                                  const Eigen::VectorXd& goal, const PlannerOptions& options);

/// A plan made on the exact checker itself, as a VerifiedPlan whose verify and repair times are
/// 0 (there is nothing to verify), so that it compares with planVerified's results.
VerifiedPlan planExactly(const std::shared_ptr<const CollisionChecker>& exact,
                         const JointLimits& limits, const Eigen::VectorXd& start,
                         const Eigen::VectorXd& goal, const PlannerOptions& options);

}  // namespace fastron
