#include "fastron/planning/verify_repair.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <string>

#include "fastron/core/error.h"
#include "fastron/core/hybrid_checker.h"
#include "fastron/core/model_checker.h"
#include "fastron/core/recording_checker.h"
#include "fastron/planning/motion.h"
#include "fastron/planning/parallel_check.h"
#include "fastron/planning/trajectory_optimization.h"

namespace fastron {
namespace {

using Clock = std::chrono::steady_clock;

bool contains(const std::vector<std::size_t>& sorted, std::size_t i) {
  return std::binary_search(sorted.begin(), sorted.end(), i);
}

bool freeUnder(const CollisionSource& source, const Eigen::VectorXd& q) {
  return firstCollision(source, q.data(), 1, static_cast<std::size_t>(q.size())) == 1;
}

/// True when the straight motion from a to b (b checked, a not) is free under `source` at
/// `resolution`.
bool motionFree(const CollisionSource& source, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                double resolution) {
  const auto dim = static_cast<std::size_t>(a.size());
  const std::size_t n = segmentCount(a, b, resolution);
  std::vector<double> states;
  motionStates(a.data(), b.data(), dim, n, states);
  return firstCollision(source, states.data(), n, dim) == n;
}

/// `end` itself when `approximate` finds it free; else the first of up to 64 uniform samples in
/// balls of growing radius (0.05 to 1.6 joint units) around it, within the limits, that both
/// checkers find free and that the exact checker can reach from `end` in a straight line (so the
/// stretch from the true end needs no repair: an exact plan of it out of a grasp took 30-330 ms
/// on the mesh Panda); std::nullopt when there is none. `approximateUse` counts the approximate
/// checker's answers and their time.
std::optional<Eigen::VectorXd> substituteFor(const Eigen::VectorXd& end,
                                             const CollisionSource& approximate,
                                             const CollisionSource& exact,
                                             const JointLimits& limits, double resolution,
                                             SourceUseCounter& approximateUse) {
  const auto dim = static_cast<std::size_t>(end.size());
  const auto freeUnderApproximate = [&](const Eigen::VectorXd& q) {
    return firstCollision(approximate, q.data(), 1, dim, approximateUse) == 1;
  };
  if (freeUnderApproximate(end)) return end;
  Rng rng(1);  // fixed: the same query gets the same substitute
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit;
  for (double radius = 0.05; radius <= 1.6; radius *= 2) {
    for (int attempt = 0; attempt < 64; ++attempt) {
      Eigen::VectorXd direction(end.size());
      for (auto& v : direction) v = gauss(rng);
      const double r = radius * std::pow(unit(rng), 1.0 / static_cast<double>(dim));
      const Eigen::VectorXd q =
          (end + r * direction.normalized()).cwiseMax(limits.lower()).cwiseMin(limits.upper());
      if (freeUnderApproximate(q) && motionFree(exact, end, q, resolution)) return q;
    }
  }
  return std::nullopt;
}

/// Where a walk in order from `from` towards `to` at `resolution` first meets a state that
/// `source` finds colliding.
struct FirstCollisionToward {
  Eigen::VectorXd lastFree;   ///< the state before it (`from` itself when the first step collides)
  Eigen::VectorXd colliding;  ///< that state
};

/// The walk above; both states are `to` when none collides. The caller knows `from` to be free.
FirstCollisionToward firstCollisionToward(const CollisionSource& source,
                                          const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                                          double resolution) {
  // Rows 0..n: `from`, the states a check of this motion at `resolution` looks at, `to`.
  const Configurations states = statesAlongPath({from, to}, resolution);
  const auto dim = static_cast<std::size_t>(from.size());
  const auto n = static_cast<std::size_t>(states.rows()) - 1;
  // Checked from row 1 on, so row `first` is the last free state (`to` when none collides).
  const std::size_t first = firstCollision(source, states.data() + dim, n, dim);
  return {states.row(static_cast<Eigen::Index>(first)).transpose(),
          states.row(static_cast<Eigen::Index>(std::min(first + 1, n))).transpose()};
}

/// A hybrid's band that trusts the model's "free" (a score below 0) and asks the exact checker
/// about everything else.
constexpr UncertaintyBand kAskEveryCollision{0, std::numeric_limits<double>::infinity()};

/// The joint limits of a bridge's search: the box the ends span, grown by `margin` on every side,
/// within `limits`.
JointLimits aroundEnds(const JointLimits& limits, const Eigen::VectorXd& a,
                       const Eigen::VectorXd& b, double margin) {
  return {(a.cwiseMin(b).array() - margin).matrix().cwiseMax(limits.lower()),
          (a.cwiseMax(b).array() + margin).matrix().cwiseMin(limits.upper())};
}

void checkExact(const std::shared_ptr<const CollisionChecker>& exact, const JointLimits& limits) {
  if (!exact) throw InvalidArgument("verify and repair: the exact checker is a null pointer");
  if (exact->dof() != limits.dim()) {
    throw InvalidArgument("verify and repair: " + exact->name() + " checks " +
                          std::to_string(exact->dof()) + " joints but the joint limits have " +
                          std::to_string(limits.dim()));
  }
}

/// The check of `path` (as checkPathParallel) where the edges flagged in `knownFree` are free
/// without a check: an earlier round checked them, and a repair kept them as they were. Each run
/// of the other edges is checked as a path of its own (its end waypoints too).
PathCheck checkNotKnownFree(const CollisionChecker& exact, const JointPath& path,
                            const std::vector<bool>& knownFree, double resolution) {
  if (knownFree.empty()) return checkPathParallel(exact, path, resolution);
  PathCheck result;
  const std::size_t edges = path.size() - 1;
  for (std::size_t first = 0; first < edges;) {
    if (knownFree[first]) {
      ++first;
      continue;
    }
    std::size_t end = first;  // one past the run's last edge
    while (end < edges && !knownFree[end]) ++end;
    const JointPath run(path.begin() + static_cast<std::ptrdiff_t>(first),
                        path.begin() + static_cast<std::ptrdiff_t>(end) + 1);
    // Runs are apart by a known-free edge at least, so they share no waypoint.
    const PathCheck check = checkPathParallel(exact, run, resolution);
    for (const std::size_t w : check.invalidWaypoints) result.invalidWaypoints.push_back(first + w);
    for (const std::size_t e : check.invalidEdges) result.invalidEdges.push_back(first + e);
    first = end;
  }
  return result;
}

/// The waypoints that replace a colliding stretch; `pushed` when gradient repair made them.
struct Bridge {
  JointPath waypoints;
  bool pushed = false;
};

/// Gradient repair: a path between the ends of a stretch (given as the waypoints kept on either
/// side and those between) that a model finds free, or nothing.
using StretchPush = std::function<std::optional<JointPath>(const JointPath& stretch)>;

/// The waypoints that replace the colliding stretch between waypoints i and j of `old` (after
/// old[i], up to old[j]), or nothing when no bridge is found in the time given. The bridge joins
/// the free states next to the stretch's first and last collisions, not its waypoints: a
/// simplified path's edges are long, and a plan between their ends replans what was free of the
/// motion too. It is short, so it gets options.verify.stretchShare of the time and shortcuts
/// without smoothing (on the mesh Panda, smoothing took two thirds of a repair and the final paths
/// were as long without it). It is planned on `relaxed` when given, unless that finds the stretch's
/// first collision free (the robot against itself, when it checks the obstacles alone): its bridge
/// would keep that collision for the next round to bridge again. With `push` (gradient repair), the
/// stretch from the waypoint kept before it to the one kept after it is first pushed out of
/// collision on a model, and that path is kept when `exact` finds it free (before the free states
/// next to the collisions are looked for: a bridge alone needs them).
std::optional<Bridge> bridgeStretch(const JointPath& old, std::size_t i, std::size_t j,
                                    const std::shared_ptr<const CollisionChecker>& relaxed,
                                    const std::shared_ptr<const CollisionChecker>& exact,
                                    const JointLimits& limits, const PlannerOptions& options,
                                    const StretchPush& push) {
  if (push) {
    // From the waypoints kept on either side: the free states next to the collisions lie on
    // the obstacle's surface, where a model's smooth boundary may still say "collides".
    const JointPath stretch(old.begin() + static_cast<std::ptrdiff_t>(i),
                            old.begin() + static_cast<std::ptrdiff_t>(j) + 1);
    const std::optional<JointPath> pushed = push(stretch);
    if (pushed && checkPathParallel(*exact, *pushed, options.resolution).valid())
      return Bridge{JointPath(pushed->begin() + 1, pushed->end()), true};
  }
  const FirstCollisionToward entry =
      firstCollisionToward(exact, old[i], old[i + 1], options.resolution);
  const Eigen::VectorXd& from = entry.lastFree;
  const Eigen::VectorXd to =
      firstCollisionToward(exact, old[j], old[j - 1], options.resolution).lastFree;
  const bool relaxedSeesIt = relaxed && !freeUnder(relaxed, entry.colliding);
  const std::shared_ptr<const CollisionChecker>& bridgeChecker = relaxedSeesIt ? relaxed : exact;
  PlannerOptions stretchOptions = options;
  stretchOptions.timeLimit = options.timeLimit * options.verify.stretchShare;
  stretchOptions.simplification = PathSimplification::Shortcuts;
  // Searched near its ends first: with the whole joint range the planner's samples and long
  // default edges wander far from a graze, and each exact edge check costs milliseconds on a mesh
  // robot (box family: repairs of 0.09-0.29 s, as long as FCL's whole plans); then in the whole
  // range, for an obstacle whose way round lies farther out.
  PlanResult bridge =
      planMotion(bridgeChecker, aroundEnds(limits, from, to, options.verify.bridgeMargin), from, to,
                 stretchOptions);
  if (!bridge.solved()) bridge = planMotion(bridgeChecker, limits, from, to, stretchOptions);
  if (!bridge.solved()) return std::nullopt;
  // Joined to the waypoints kept on either side.
  Bridge out;
  if (!from.isApprox(old[i])) out.waypoints.push_back(from);
  out.waypoints.insert(out.waypoints.end(), bridge.path.begin() + 1, bridge.path.end());
  if (!to.isApprox(old[j])) out.waypoints.push_back(old[j]);
  return out;
}

/// verifyAndRepair, whose first check of `path` is `known` when given (the caller made it), and
/// whose first round plans its bridges on `relaxed` when given: a checker that never says
/// "collides" where `exact` finds the robot free, so a bridge is at worst wrong, and the next
/// round's verification catches that.
VerifiedPlan repairChecked(const JointPath& path, const std::optional<PathCheck>& known,
                           const std::shared_ptr<const CollisionChecker>& exact,
                           const JointLimits& limits, const PlannerOptions& options,
                           const std::shared_ptr<const CollisionChecker>& relaxed = nullptr,
                           const StretchPush& push = {}) {
  // A stretch repaired on the exact checker is free, so a round after it suffices; one more
  // when the first round's bridges are on a relaxed checker.
  const int rounds = relaxed ? 4 : 3;
  VerifiedPlan result;
  result.path = path;
  // Per edge of result.path: checked free by an earlier round and kept since (empty: none).
  std::vector<bool> knownFree;
  for (int round = 0; round < rounds; ++round) {
    auto began = Clock::now();
    const PathCheck check =
        round == 0 && known ? *known
                            : checkNotKnownFree(*exact, result.path, knownFree, options.resolution);
    result.verifyTime += Clock::now() - began;
    if (check.valid()) {
      result.status = PlanStatus::Solved;
      result.failure.clear();
      return result;
    }
    const JointPath& old = result.path;
    if (old.empty() || contains(check.invalidWaypoints, 0)) {
      result.status = PlanStatus::InvalidStart;
      result.failure = "the path's start collides under " + exact->name();
      return result;
    }
    if (contains(check.invalidWaypoints, old.size() - 1)) {
      result.status = PlanStatus::InvalidGoal;
      result.failure = "the path's goal collides under " + exact->name();
      return result;
    }

    began = Clock::now();
    JointPath repaired{old.front()};
    std::vector<bool> repairedKnownFree;  // per edge of `repaired`
    // Every edge from here to the next waypoint kept is new, so not known free.
    const auto addNew = [&](const Eigen::VectorXd& waypoint) {
      repaired.push_back(waypoint);
      repairedKnownFree.push_back(false);
    };
    std::size_t i = 0;  // the last valid waypoint kept
    while (i + 1 < old.size()) {
      if (!contains(check.invalidEdges, i) && !contains(check.invalidWaypoints, i + 1)) {
        repaired.push_back(old[++i]);
        repairedKnownFree.push_back(true);
        continue;
      }
      // Excise up to the next valid waypoint and bridge the gap (a waypoint the approximate plan
      // left in a pocket of free space may have no short way out: then the whole motion is
      // planned again on the exact checker).
      std::size_t j = i + 1;
      while (contains(check.invalidWaypoints, j)) ++j;
      ++result.invalidStretches;
      const std::optional<Bridge> bridge =
          bridgeStretch(old, i, j, round == 0 ? relaxed : nullptr, exact, limits, options, push);
      if (!bridge) {
        const PlanResult whole = planMotion(exact, limits, old.front(), old.back(), options);
        if (!whole.solved()) {
          result.repairTime += Clock::now() - began;
          result.status = PlanStatus::Timeout;
          result.failure = "could not replan the stretch between waypoints " + std::to_string(i) +
                           " and " + std::to_string(j) + " on " + exact->name() +
                           ", nor the whole path (" + std::string(toString(whole.status)) + ")";
          return result;
        }
        repaired = whole.path;
        repairedKnownFree.assign(repaired.size() - 1, false);
        result.wholePathReplanned = true;
        break;
      }
      std::for_each(bridge->waypoints.begin(), bridge->waypoints.end(), addNew);
      result.gradientRepairs += bridge->pushed ? 1 : 0;
      i = j;
    }
    result.path = std::move(repaired);
    knownFree = std::move(repairedKnownFree);
    result.repairTime += Clock::now() - began;
  }
  result.status = PlanStatus::Timeout;
  result.failure = "the path still collided after " + std::to_string(rounds) + " repair rounds";
  return result;
}

}  // namespace

VerifiedPlan verifyAndRepair(const JointPath& path,
                             const std::shared_ptr<const CollisionChecker>& exact,
                             const JointLimits& limits, const PlannerOptions& options) {
  checkExact(exact, limits);
  validate(options);
  return repairChecked(path, std::nullopt, exact, limits, options);
}

namespace {

/// A plan on an approximate source within options.verify.approximateShare of the time limit.
struct ApproximatePlan {
  PlanResult plan;
  bool substituteEnds = false;
};

PlanAttempt attemptOf(const CollisionSource& source, const PlanResult& plan,
                      bool substituteEnds = false) {
  return {.source = sourceName(source),
          .onModel = std::holds_alternative<std::shared_ptr<const Model>>(source),
          .status = plan.status,
          .time = plan.time,
          .simplifyTime = plan.simplifyTime,
          .checks = plan.checks,
          .checkTime = plan.checkTime,
          .substituteEnds = substituteEnds};
}

ApproximatePlan planApproximately(const CollisionSource& approximate,
                                  const std::shared_ptr<const CollisionChecker>& exact,
                                  const JointLimits& limits, const Eigen::VectorXd& start,
                                  const Eigen::VectorXd& goal, const PlannerOptions& options) {
  const auto began = Clock::now();
  PlannerOptions approximateOptions = options;
  approximateOptions.timeLimit = options.timeLimit * options.verify.approximateShare;
  ApproximatePlan result{planMotion(approximate, limits, start, goal, approximateOptions)};
  PlanResult& plan = result.plan;
  if ((plan.status == PlanStatus::InvalidStart || plan.status == PlanStatus::InvalidGoal) &&
      freeUnder(exact, start) && freeUnder(exact, goal)) {
    // The approximate checker is wrong about an end (a conservative model often is where the
    // robot touches an obstacle on purpose, as in a grasp). Plan on it between free
    // configurations near the ends that the exact checker reaches from them in a straight line.
    // The approximate source's answers in the search for substitutes, and in the first plan
    // when a second replaces it, are the plan's too.
    SourceUseCounter asked;
    const auto startNear =
        substituteFor(start, approximate, exact, limits, options.resolution, asked);
    const auto goalNear =
        substituteFor(goal, approximate, exact, limits, options.resolution, asked);
    if (startNear && goalNear) {
      approximateOptions.timeLimit = std::min(approximateOptions.timeLimit,
                                              options.timeLimit * options.verify.substituteShare);
      asked.add(plan.checks, plan.checkTime);
      plan = planMotion(approximate, limits, *startNear, *goalNear, approximateOptions);
      if (plan.solved()) {
        if (!startNear->isApprox(start)) plan.path.insert(plan.path.begin(), start);
        if (!goalNear->isApprox(goal)) plan.path.push_back(goal);
      }
      result.substituteEnds = true;
    }
    // The search for substitutes (the exact checker's straight motions among them) is part of
    // the plan's time.
    plan.time = Clock::now() - began;
    plan.checks += asked.total().answered;
    plan.checkTime += asked.total().time;
  }
  return result;
}

/// Plans on each source of `chain` in turn (with `chainOptions`) until one finds a path, then
/// verifies and repairs it (the first round's bridges on `relaxed` when given, as in
/// repairChecked); when none does, plans the whole motion on the exact checker (both with
/// `options`).
VerifiedPlan planAndRepair(const std::vector<CollisionSource>& chain,
                           const std::shared_ptr<const CollisionChecker>& exact,
                           const JointLimits& limits, const Eigen::VectorXd& start,
                           const Eigen::VectorXd& goal, const PlannerOptions& options,
                           const PlannerOptions& chainOptions,
                           const std::shared_ptr<const CollisionChecker>& relaxed = nullptr,
                           const StretchPush& push = {}) {
  std::chrono::nanoseconds planTime{0};
  bool substituteEnds = false;
  std::vector<PlanAttempt> attempts;
  for (const CollisionSource& source : chain) {
    const ApproximatePlan attempt =
        planApproximately(source, exact, limits, start, goal, chainOptions);
    planTime += attempt.plan.time;
    substituteEnds = substituteEnds || attempt.substituteEnds;
    attempts.push_back(attemptOf(source, attempt.plan, attempt.substituteEnds));
    if (attempt.plan.solved()) {
      VerifiedPlan result =
          repairChecked(attempt.plan.path, std::nullopt, exact, limits, options, relaxed, push);
      result.attempts = std::move(attempts);
      result.planTime = planTime;
      result.simplifyTime = attempt.plan.simplifyTime;
      result.substituteEnds = attempt.substituteEnds;
      // A stretch not bridged makes verifyAndRepair plan the whole motion on `exact`.
      result.plannedOn = result.wholePathReplanned ? exact->name() : sourceName(source);
      return result;
    }
  }
  // No approximate source found a path (or each thinks an end collides): plan it all exactly.
  const auto began = Clock::now();
  const PlanResult exactPlan = planMotion(exact, limits, start, goal, options);
  const auto repairTime = Clock::now() - began;
  attempts.push_back(attemptOf(exact, exactPlan));
  VerifiedPlan result;
  if (exactPlan.solved()) {
    result = verifyAndRepair(exactPlan.path, exact, limits, options);  // the final check
    result.invalidStretches += 1;
  } else {
    result.status = exactPlan.status;
    result.failure = std::string(toString(exactPlan.status)) + " under " + exact->name();
  }
  result.attempts = std::move(attempts);
  result.planTime = planTime;
  result.repairTime += repairTime;
  result.wholePathReplanned = true;
  result.substituteEnds = substituteEnds;
  result.plannedOn = exact->name();
  return result;
}

}  // namespace

VerifiedPlan planVerified(const CollisionSource& approximate,
                          const std::shared_ptr<const CollisionChecker>& exact,
                          const JointLimits& limits, const Eigen::VectorXd& start,
                          const Eigen::VectorXd& goal, const PlannerOptions& options) {
  checkExact(exact, limits);
  const auto recorder = std::make_shared<RecordingChecker>(exact);
  VerifiedPlan result =
      planAndRepair({approximate}, recorder, limits, start, goal, options, options);
  result.exactAnswers = recorder->take();
  result.exactChecks = recorder->callCount();
  return result;
}

VerifiedPlan planVerifiedOptimistically(const std::shared_ptr<const CollisionChecker>& approximate,
                                        const std::shared_ptr<const CollisionChecker>& exact,
                                        const JointLimits& limits, const Eigen::VectorXd& start,
                                        const Eigen::VectorXd& goal,
                                        const PlannerOptions& options) {
  checkExact(exact, limits);
  if (!approximate) throw InvalidArgument("planVerifiedOptimistically: no approximate checker");
  const auto recorder = std::make_shared<RecordingChecker>(exact);
  const auto confirmed = std::make_shared<const AllOfChecker>(
      std::vector<std::shared_ptr<const CollisionChecker>>{approximate, recorder});
  std::vector<CollisionSource> chain;
  chain.reserve(2);  // (filled one by one: GCC 12 warns falsely on a list of variants)
  chain.emplace_back(approximate);
  chain.emplace_back(confirmed);
  VerifiedPlan result = planAndRepair(chain, recorder, limits, start, goal, options, options);
  result.exactAnswers = recorder->take();
  result.exactChecks = recorder->callCount();
  return result;
}

VerifiedPlan planVerified(const CalibratedModel& model,
                          const std::shared_ptr<const CollisionChecker>& exact,
                          const JointLimits& limits, const Eigen::VectorXd& start,
                          const Eigen::VectorXd& goal, const PlannerOptions& options) {
  checkExact(exact, limits);
  if (!model.model) throw InvalidArgument("planVerified: the model is a null pointer");
  const auto recorder = std::make_shared<RecordingChecker>(exact);
  std::vector<CollisionSource> chain;
  chain.reserve(2);  // (filled one by one: GCC 12 warns falsely on a list of variants)
  chain.emplace_back(model.model);
  if (model.calibration.colliding + model.calibration.free > 0) {
    chain.emplace_back(
        std::make_shared<HybridChecker>(model.model, recorder, model.calibration.band));
  }
  VerifiedPlan result = planAndRepair(chain, recorder, limits, start, goal, options, options);
  result.exactAnswers = recorder->take();
  result.exactChecks = recorder->callCount();
  return result;
}

/// With options.verify.oracleRelaxesExact, the proxy's oracle, which answers where verification
/// catches a wrong "free" later: the hybrid's "collides" and the first repair round's bridges (not
/// recorded: its answers are not the exact checker's). Wrapped to count its answers for one plan.
std::shared_ptr<const CountedChecker> relaxedOracle(
    const ProxyCollisionDetector& proxy, const std::shared_ptr<const CollisionChecker>& exact,
    const PlannerOptions& options) {
  if (!options.verify.oracleRelaxesExact || proxy.oracle() == exact) return nullptr;
  return std::make_shared<const CountedChecker>(proxy.oracle());
}

/// What the rounds of planVerifiedLearning on the model spent and learned, before the plan that
/// ended them.
struct LearningRounds {
  std::chrono::nanoseconds planTime{0}, simplifyTime{0}, verifyTime{0}, learnTime{0};
  std::size_t relearned = 0;
  bool substituteEnds = false;
  std::vector<PlanAttempt> attempts;  // on the model, before those of the final plan
  Dataset answers;                    // the exact answers of the rounds that learned
};

/// Adds the rounds' times, attempts and answers to the plan that ended them, and the answers and
/// checks the recorder holds.
void addRounds(VerifiedPlan& result, LearningRounds rounds, RecordingChecker& recorder) {
  result.planTime += rounds.planTime + rounds.learnTime;
  result.simplifyTime += rounds.simplifyTime;
  result.learnTime = rounds.learnTime;
  result.verifyTime += rounds.verifyTime;
  result.relearned = rounds.relearned;
  result.substituteEnds = result.substituteEnds || rounds.substituteEnds;
  result.attempts.insert(result.attempts.begin(), rounds.attempts.begin(), rounds.attempts.end());
  append(rounds.answers, recorder.take());
  result.exactAnswers = std::move(rounds.answers);
  result.exactChecks = recorder.callCount();
}

/// When the model closes the way. Near walls it says "collides" with confidence where the robot
/// is free (outside any calibrated band), so a hybrid plans next that trusts only its "free" and
/// asks about every "collides" (the relaxed oracle when there is one): in the generated cage
/// family 74-83% of those answers were "free". Then `recorder` (the exact checker) plans the whole
/// motion; the path is verified and repaired.
VerifiedPlan planOnOptimisticHybrid(const std::shared_ptr<const Model>& model,
                                    const std::shared_ptr<RecordingChecker>& recorder,
                                    const std::shared_ptr<const CollisionChecker>& relaxed,
                                    const JointLimits& limits, const Eigen::VectorXd& start,
                                    const Eigen::VectorXd& goal, const PlannerOptions& options,
                                    const StretchPush& push) {
  const std::vector<CollisionSource> optimistic{
      std::make_shared<HybridChecker>(model, relaxed ? relaxed : recorder, kAskEveryCollision)};
  PlannerOptions hybridOptions = options;
  hybridOptions.range = optimisticHybridRange(options, limits);
  // From half the planner's range down to the planner's shortest (RangeSchedule), not below.
  if (options.verify.hybridRange == 0 && options.rangeHalvings > 0) {
    hybridOptions.rangeHalvings = options.rangeHalvings - 1;
  }
  return planAndRepair(optimistic, recorder, limits, start, goal, options, hybridOptions, relaxed,
                       push);
}

/// Gradient repair's push for planVerifiedLearning: the model learns the stretch's exact labels
/// (its states at the model's step, asked here of `recorder`: verification labels only the states
/// up to each edge's first collision) and every other exact answer it got wrong so far (kept in
/// `answers`), then pushes the stretch out of its collisions (nothing when it stays in them). No
/// push (an empty function) unless options.verify.gradientRepair.
StretchPush gradientPush(ProxyCollisionDetector& proxy,
                         const std::shared_ptr<RecordingChecker>& recorder, Dataset& answers,
                         const JointLimits& limits, const PlannerOptions& options) {
  if (!options.verify.gradientRepair) return {};
  return [&proxy, recorder, &answers, limits, pushOptions = gradientRepairOptions(options)](
             const JointPath& stretch) -> std::optional<JointPath> {
    (void)recorder->inCollisionBatch(statesAlongPath(stretch, pushOptions.modelResolution));
    const Dataset recorded = recorder->take();
    const Dataset missed = answersMissedBy(*proxy.model(), recorded);
    append(answers, recorded);
    if (missed.size() > 0) {
      proxy.addObservations(missed);
      proxy.learnObservations();
    }
    OptimizedTrajectory pushed = optimizeTrajectory(
        *proxy.model(), limits, densePath(stretch, pushOptions.spacing), pushOptions);
    if (!pushed.freeOnModel) return std::nullopt;
    return std::move(pushed.path);
  };
}

VerifiedPlan planVerifiedLearning(ProxyCollisionDetector& proxy,
                                  const std::shared_ptr<const CollisionChecker>& exact,
                                  const JointLimits& limits, const Eigen::VectorXd& start,
                                  const Eigen::VectorXd& goal, const PlannerOptions& options) {
  checkExact(exact, limits);
  validate(options);
  const auto recorder = std::make_shared<RecordingChecker>(exact);
  LearningRounds rounds;
  VerifiedPlan result;
  JointPath lastPath;  // the last path on the model that verification found colliding
  PathCheck lastCheck;
  PlannerOptions roundOptions = options;
  roundOptions.verify.approximateShare =
      std::min(options.verify.approximateShare, options.verify.modelShare);
  const std::shared_ptr<const CountedChecker> relaxed = relaxedOracle(proxy, exact, options);
  const StretchPush push = gradientPush(proxy, recorder, rounds.answers, limits, options);
  // Repairs `path` (its first check given when known), as planVerified does.
  const auto repair = [&](const JointPath& path, const std::optional<PathCheck>& check) {
    VerifiedPlan repaired = repairChecked(path, check, recorder, limits, options, relaxed, push);
    repaired.plannedOn = repaired.wholePathReplanned ? exact->name() : sourceName(proxy.model());
    return repaired;
  };
  for (unsigned round = 0;; ++round) {
    const std::shared_ptr<const Model> model = proxy.model();
    const ApproximatePlan attempt =
        planApproximately(model, recorder, limits, start, goal, roundOptions);
    rounds.planTime += attempt.plan.time;
    rounds.simplifyTime += attempt.plan.simplifyTime;
    rounds.substituteEnds = rounds.substituteEnds || attempt.substituteEnds;
    rounds.attempts.push_back(attemptOf(model, attempt.plan, attempt.substituteEnds));
    if (!attempt.plan.solved() && round > 0) {
      // What the model learned closed its way: repair the last path instead, as planVerified
      // would have.
      result = repair(lastPath, lastCheck);
      break;
    }
    if (!attempt.plan.solved()) {
      result = planOnOptimisticHybrid(model, recorder, relaxed, limits, start, goal, options, push);
      break;
    }
    if (round == options.verify.learningRounds) {
      result = repair(attempt.plan.path, std::nullopt);
      break;
    }
    const auto verifyBegan = Clock::now();
    const PathCheck check = checkPathParallel(*recorder, attempt.plan.path, options.resolution);
    rounds.verifyTime += Clock::now() - verifyBegan;
    if (check.valid()) {
      result.status = PlanStatus::Solved;
      result.path = attempt.plan.path;
      result.plannedOn = sourceName(model);
      break;
    }
    if (round == 0) {
      // A plan on the corrected model gets the first one's time a few times over (at least 50
      // ms), not the whole share: when what it learned closes the way, searching on costs more
      // than repairing the last path.
      const double box =
          std::max(0.05, 4 * std::chrono::duration<double>(attempt.plan.time).count());
      roundOptions.verify.approximateShare =
          std::min(options.verify.approximateShare, box / options.timeLimit);
    }
    const auto learnBegan = Clock::now();
    const Dataset recorded = recorder->take();
    const Dataset missed = answersMissedBy(*model, recorded);
    append(rounds.answers, recorded);
    if (missed.size() == 0) {
      // Verification's states all answered as the model does (the planner looked at others):
      // learning would change nothing, so the path is repaired.
      result = repair(attempt.plan.path, check);
      break;
    }
    proxy.addObservations(missed);
    proxy.learnObservations();
    rounds.learnTime += Clock::now() - learnBegan;
    ++rounds.relearned;
    lastPath = attempt.plan.path;
    lastCheck = check;
  }
  addRounds(result, std::move(rounds), *recorder);
  result.relaxedChecks = relaxed ? relaxed->callCount() : 0;
  return result;
}

VerifiedPlan planExactly(const std::shared_ptr<const CollisionChecker>& exact,
                         const JointLimits& limits, const Eigen::VectorXd& start,
                         const Eigen::VectorXd& goal, const PlannerOptions& options) {
  checkExact(exact, limits);
  const PlanResult plan = planMotion(exact, limits, start, goal, options);
  VerifiedPlan result;
  result.attempts.push_back(attemptOf(exact, plan));
  result.exactChecks = plan.checks;  // the planner asked `exact` alone
  result.status = plan.status;
  result.path = plan.path;
  result.planTime = plan.time;
  result.simplifyTime = plan.simplifyTime;
  result.plannedOn = exact->name();
  if (!plan.solved()) result.failure = toString(plan.status);
  return result;
}

}  // namespace fastron
