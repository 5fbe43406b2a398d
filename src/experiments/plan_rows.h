#pragma once
// What the planning experiments share (internal to the experiments library): a plan's outcome
// for its result row, planning one query with every checker, drawing free queries, and the
// Markdown tables of plan results.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fastron/core/collision_checker.h"
#include "fastron/core/error.h"
#include "fastron/core/joint_limits.h"

#include "fastron/experiments/plan_results.h"
#include "fastron/planning/planner.h"
#include "fastron/planning/verify_repair.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron::experiments {

using CheckerPtr = std::shared_ptr<const CollisionChecker>;

struct MethodPlan {
  std::string method;
  VerifiedPlan plan;
  /// Of the collision queries of the plan itself (before verification), the share FCL answered.
  double exactShare = 0;
};

/// The plan's outcome for a result row; `audit` is an FCL checker the planner never used, which
/// re-checks a solved path at `resolution`.
PlanOutcome outcomeOf(const MethodPlan& method, const CollisionChecker& audit, double resolution);

/// Fastron, Hybrid (Fastron with FCL inside the model's calibrated band) and GJK, each verified
/// and repaired with FCL, and FCL itself, on one query; returned in that order. Hybrid only when
/// the band was calibrated; GJK only when given. The methods take turns at planning first: method
/// `turn` mod their count first (pass the query's index), so that none always meets cold caches.
/// Before each method plans, seedPlanners(seed, turn): a run repeats its plans, and two builds
/// compared on one seed differ only where their checkers' answers or their speed do.
std::vector<MethodPlan> planWithEachChecker(const CalibratedModel& model, const CheckerPtr& gjk,
                                            const CheckerPtr& fcl, const JointLimits& limits,
                                            const Eigen::VectorXd& start,
                                            const Eigen::VectorXd& goal,
                                            const PlannerOptions& options, std::uint64_t seed,
                                            std::size_t turn);

bool freeUnder(const CollisionChecker& checker, const Eigen::VectorXd& q);

/// A configuration free under `checker` drawn by `sample`, or nothing after `attempts` tries.
template <class Sample>
std::optional<Eigen::VectorXd> trySampleFree(const CollisionChecker& checker, Sample&& sample,
                                             std::size_t attempts) {
  for (std::size_t i = 0; i < attempts; ++i) {
    Eigen::VectorXd q = sample();
    if (freeUnder(checker, q)) return q;
  }
  return std::nullopt;
}

/// A configuration free under `checker` drawn by `sample`; throws Error after `attempts` tries.
template <class Sample>
Eigen::VectorXd sampleFree(const CollisionChecker& checker, Sample&& sample, const char* what,
                           std::size_t attempts = 200000) {
  if (auto q = trySampleFree(checker, sample, attempts)) return *q;
  throw Error(std::string("found no collision-free ") + what + " in " + std::to_string(attempts) +
              " samples");
}

Eigen::VectorXd uniformIn(const JointLimits& limits, Rng& rng);

/// A uniform configuration for which `reaches` holds; throws Error naming `where` after 10^7 tries.
template <class Reaches>
Eigen::VectorXd sampleReaching(Reaches&& reaches, const JointLimits& limits, Rng& rng,
                               const char* where) {
  for (int i = 0; i < 10'000'000; ++i) {
    Eigen::VectorXd q = uniformIn(limits, rng);
    if (reaches(q)) return q;
  }
  throw Error(std::string("no configuration in 10^7 samples reaches ") + where);
}

/// Start and goal on opposite sides of the workspace: the first joint (the shoulder's yaw) in
/// the lowest and the highest 30% of its range, the others uniform; both free under `fcl`.
std::pair<Eigen::VectorXd, Eigen::VectorXd> oppositeEnds(const JointLimits& limits,
                                                         const CollisionChecker& fcl, Rng& rng);
/// As oppositeEnds, or nothing when either side has no free configuration in `attempts` samples
/// (moving obstacles can block one side of the workspace for a while).
std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>> tryOppositeEnds(
    const JointLimits& limits, const CollisionChecker& fcl, Rng& rng, std::size_t attempts);

std::string progressLine(const std::string& what, std::size_t i, std::size_t n);

/// Which rows a table or a statistic takes; every row when empty.
using RowFilter = std::function<bool(const PlanRow&)>;

/// The methods of the rows matching `where`, in order of appearance.
std::vector<std::string> methodsOf(const PlanRows& r, const RowFilter& where = {});

/// The Markdown table of plan results of the rows matching `where`, one line per (planner,
/// method): success rate, then means ± std over solved plans.
std::string planTable(const PlanRows& r, const RowFilter& where,
                      const std::vector<std::string>& planners);

/// "Where the time goes": per (planner, method), medians over solved plans of the plan's time,
/// of its attempts that found no path (a model closing the way), of simplification, of its
/// attempts' sources answering (and the median share of the attempts' time), of verify
/// and repair, of the plans made before verification, of the checks their sources answered, and
/// of those the exact checker and a relaxed oracle answered; then a line per method of the share
/// of its plans on a bare model spent in model queries, and their time per query.
std::string timeBreakdown(const PlanRows& r, const RowFilter& where,
                          const std::vector<std::string>& planners);

/// Per planner, FCL's total time over each other method's, from means and from medians over
/// solved plans.
std::string speedups(const PlanRows& r, const RowFilter& where,
                     const std::vector<std::string>& planners);

/// One line "LEAD: PLANNER: METHOD N.Nx ...; PLANNER: ...": per planner, the median (or mean) of
/// `value` over FCL's solved rows that `where` keeps, over the same of each other method.
std::string ratioLine(const PlanRows& r, const RowFilter& where,
                      const std::vector<std::string>& planners, const std::string& lead,
                      const std::function<double(const PlanRow&)>& value, bool median);

std::vector<std::string> plannerNames(const std::vector<PlannerType>& types);

/// The planner options of an experiment's options `o` (resolution, time limit, simplification,
/// and the range where `o` has one) for a planner of `type`.
PlannerOptions plannerOptions(const auto& o, PlannerType type) {
  PlannerOptions options{.type = type,
                         .resolution = o.resolution,
                         .modelResolution = o.modelResolution,
                         .timeLimit = o.timeLimit,
                         .simplifyTime = o.simplifyTime,
                         .simplification = o.simplification,
                         .verify = {}};
  if constexpr (requires { o.range; }) options.range = o.range;  // where an experiment has one
  if constexpr (requires { o.rangeStage; }) {
    if (o.rangeStage) options.rangeStage = *o.rangeStage;
  }
  if constexpr (requires { o.gradientRepair; }) options.verify.gradientRepair = o.gradientRepair;
  return options;
}

/// The edge steps of an experiment's plans for its report: "0.03 rad (0.09 rad on a model and its
/// hybrid)".
std::string edgeSteps(const auto& o, const std::string& unit) {
  std::ostringstream text;
  text << o.resolution << ' ' << unit << " ("
       << modelStep(plannerOptions(o, PlannerType::RrtConnect)) << ' ' << unit
       << " on a model and its hybrid)";
  return text.str();
}

}  // namespace fastron::experiments
