#include "plan_rows.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iterator>
#include <sstream>

#include "fastron/core/active_learning.h"
#include "fastron/core/hybrid_checker.h"
#include "fastron/experiments/statistics.h"
#include "fastron/planning/motion.h"

namespace fastron::experiments {
PlanOutcome outcomeOf(const MethodPlan& method, const CollisionChecker& audit, double resolution) {
  const VerifiedPlan& plan = method.plan;
  PlanOutcome o;
  o.solved = plan.solved();
  o.status = plan.failure.empty() ? std::string(toString(plan.status)) : plan.failure;
  o.planSeconds = inSeconds(plan.planTime);
  o.simplifySeconds = inSeconds(plan.simplifyTime);
  o.verifySeconds = inSeconds(plan.verifyTime);
  o.repairSeconds = inSeconds(plan.repairTime);
  o.totalSeconds = inSeconds(plan.totalTime());
  o.waypoints = plan.path.size();
  o.repairedStretches = plan.invalidStretches;
  o.gradientRepairs = plan.gradientRepairs;
  o.relearned = plan.relearned;
  o.learnSeconds = inSeconds(plan.learnTime);
  o.wholeMotionReplanned = plan.wholePathReplanned;
  o.substituteEnds = plan.substituteEnds;
  o.exactShare = method.exactShare;
  o.attempts = plan.attempts.size();
  double attemptSeconds = 0;
  for (const PlanAttempt& attempt : plan.attempts) {
    attemptSeconds += inSeconds(attempt.time);
    if (attempt.status != PlanStatus::Solved) o.failedPlanSeconds += inSeconds(attempt.time);
    o.planChecks += attempt.checks;
    o.planCheckSeconds += inSeconds(attempt.checkTime);
    if (attempt.onModel) {
      o.modelPlanSeconds += inSeconds(attempt.time);
      o.modelCheckSeconds += inSeconds(attempt.checkTime);
      o.modelChecks += attempt.checks;
    }
  }
  o.planCheckShare = attemptSeconds > 0 ? o.planCheckSeconds / attemptSeconds : 0;
  o.exactChecks = plan.exactChecks;
  o.relaxedChecks = plan.relaxedChecks;
  o.plannedOn = plan.plannedOn;
  if (o.solved) {
    o.pathLength = pathLength(plan.path);
    o.collidesUnderAudit = !checkPath(audit, plan.path, resolution).valid();
  }
  return o;
}

/// Fastron, Hybrid (Fastron with FCL inside the model's calibrated band) and GJK, each verified
/// and repaired with FCL, and FCL itself, on one query. Hybrid only when the band was calibrated.
std::vector<MethodPlan> planWithEachChecker(const CalibratedModel& model, const CheckerPtr& gjk,
                                            const CheckerPtr& fcl, const JointLimits& limits,
                                            const Eigen::VectorXd& start,
                                            const Eigen::VectorXd& goal,
                                            const PlannerOptions& options, std::uint64_t seed,
                                            std::size_t turn) {
  using Plan = std::function<MethodPlan()>;
  std::vector<Plan> methods;
  methods.emplace_back([&] {
    return MethodPlan{"Fastron", planVerified(model, fcl, limits, start, goal, options), 0};
  });
  if (model.calibration.colliding + model.calibration.free > 0) {
    methods.emplace_back([&] {
      const auto hybrid = std::make_shared<HybridChecker>(model.model, fcl, model.calibration.band);
      VerifiedPlan plan = planVerified(hybrid, fcl, limits, start, goal, options);
      return MethodPlan{"Hybrid", std::move(plan), hybrid->exactShare()};
    });
  }
  if (gjk) {
    methods.emplace_back([&] {
      return MethodPlan{"GJK", planVerified(gjk, fcl, limits, start, goal, options), 0};
    });
  }
  methods.emplace_back([&] {
    return MethodPlan{"FCL", planExactly(fcl, limits, start, goal, options), 1};
  });
  // The method that plans first finds OMPL's code and the scene cold (model updates ran in
  // between): with FCL always last, bench plan's BIT* medians of FCL / Fastron were 0.3-0.6x;
  // with FCL always first, 0.7-1.2x.
  std::vector<MethodPlan> plans(methods.size());
  for (std::size_t k = 0; k < methods.size(); ++k) {
    const std::size_t m = (turn + k) % methods.size();
    seedPlanners(seed, turn);
    plans[m] = methods[m]();
  }
  return plans;
}

bool freeUnder(const CollisionChecker& checker, const Eigen::VectorXd& q) {
  return !checker.inCollision(
      std::span<const double>(q.data(), static_cast<std::size_t>(q.size())));
}

Eigen::VectorXd uniformIn(const JointLimits& limits, Rng& rng) {
  return uniformConfigurations(limits, 1, rng).row(0).transpose();
}

std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>> tryOppositeEnds(
    const JointLimits& limits, const CollisionChecker& fcl, Rng& rng, std::size_t attempts) {
  const double lo = limits.lower()[0], hi = limits.upper()[0], band = 0.3 * (hi - lo);
  std::uniform_real_distribution<double> u(0.0, band);
  // The joint values first, then the yaw: the order of draws of the queries' seeds.
  const auto lowYaw = [&] {
    Eigen::VectorXd q = uniformIn(limits, rng);
    q[0] = lo + u(rng);
    return q;
  };
  const auto highYaw = [&] {
    Eigen::VectorXd q = uniformIn(limits, rng);
    q[0] = hi - u(rng);
    return q;
  };
  auto start = trySampleFree(fcl, lowYaw, attempts);
  if (!start) return std::nullopt;
  auto goal = trySampleFree(fcl, highYaw, attempts);
  if (!goal) return std::nullopt;
  if (std::uniform_int_distribution<int>(0, 1)(rng) == 1) std::swap(*start, *goal);
  return std::pair{std::move(*start), std::move(*goal)};
}

/// Start and goal on opposite sides of the workspace: the first joint (the shoulder's yaw) in
/// the lowest and the highest 30% of its range, the others uniform; both free under `fcl`.
std::pair<Eigen::VectorXd, Eigen::VectorXd> oppositeEnds(const JointLimits& limits,
                                                         const CollisionChecker& fcl, Rng& rng) {
  constexpr std::size_t kAttempts = 200000;
  if (auto ends = tryOppositeEnds(limits, fcl, rng, kAttempts)) return std::move(*ends);
  throw Error("found no collision-free start or goal in " + std::to_string(kAttempts) +
              " samples on either side of the workspace");
}

std::string progressLine(const std::string& what, std::size_t i, std::size_t n) {
  return what + " " + std::to_string(i + 1) + "/" + std::to_string(n);
}

namespace {

/// The rows matching `where`, and `more`.
std::vector<const PlanRow*> select(const PlanRows& r, const RowFilter& where,
                                   const RowFilter& more = {}) {
  std::vector<const PlanRow*> out;
  for (const PlanRow& row : r.rows) {
    if ((!where || where(row)) && (!more || more(row))) out.push_back(&row);
  }
  return out;
}

template <class Value>
Summary summaryOf(const std::vector<const PlanRow*>& rows, Value value) {
  std::vector<double> values;
  for (const PlanRow* row : rows) values.push_back(value(row->outcome));
  return summarize(values);
}

}  // namespace

std::vector<std::string> methodsOf(const PlanRows& r, const RowFilter& where) {
  std::vector<std::string> methods;
  for (const PlanRow* row : select(r, where)) {
    if (std::find(methods.begin(), methods.end(), row->method) == methods.end()) {
      methods.push_back(row->method);
    }
  }
  return methods;
}

/// The Markdown table of plan results of the rows matching `where`, one line per (planner,
/// method): success rate, then means ± std over solved plans.
std::string planTable(const PlanRows& r, const RowFilter& where,
                      const std::vector<std::string>& planners) {
  std::ostringstream md;
  md << "| Planner | Method | Success | Plan (of which simplify) | Verify | Repair | Total | Path "
        "length (joint space) | Repaired stretches | Plans repaired | Plan queries FCL answered | "
        "Final paths colliding (FCL) |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const std::string& planner : planners) {
    for (const std::string& method : methodsOf(r, where)) {
      const auto all = select(r, where, [&](const PlanRow& row) {
        return row.planner == planner && row.method == method;
      });
      if (all.empty()) continue;
      std::vector<const PlanRow*> ok;
      std::copy_if(all.begin(), all.end(), std::back_inserter(ok),
                   [](const PlanRow* row) { return row->outcome.solved; });
      const auto stat = [&](auto value) { return summaryOf(ok, value); };
      const auto colliding = std::count_if(ok.begin(), ok.end(), [](const PlanRow* row) {
        return row->outcome.collidesUnderAudit.value_or(false);
      });
      const auto repaired = std::count_if(ok.begin(), ok.end(), [](const PlanRow* row) {
        return row->outcome.repairedStretches > 0;
      });
      char rate[64];
      std::snprintf(rate, sizeof rate, "%.2f (%zu/%zu)",
                    static_cast<double>(ok.size()) / static_cast<double>(all.size()), ok.size(),
                    all.size());
      char repairedShare[64];
      std::snprintf(repairedShare, sizeof repairedShare, "%.0f%%",
                    ok.empty()
                        ? 0.0
                        : 100.0 * static_cast<double>(repaired) / static_cast<double>(ok.size()));
      md << "| " << planner << " | " << method << " | " << rate << " | "
         << durationMeanStd(stat([](const PlanOutcome& o) { return o.planSeconds; })) << " ("
         << durationMeanStd(stat([](const PlanOutcome& o) { return o.simplifySeconds; })) << ") | "
         << durationMeanStd(stat([](const PlanOutcome& o) { return o.verifySeconds; })) << " | "
         << durationMeanStd(stat([](const PlanOutcome& o) { return o.repairSeconds; })) << " | "
         << durationMeanStd(stat([](const PlanOutcome& o) { return o.totalSeconds; })) << " | "
         << meanStd(stat([](const PlanOutcome& o) { return o.pathLength; }), 2) << " | "
         << meanStd(
                stat([](const PlanOutcome& o) { return static_cast<double>(o.repairedStretches); }),
                2)
         << " | " << repairedShare << " | "
         << meanStd(summaryOf(all, [](const PlanOutcome& o) { return o.exactShare; }), 3) << " | "
         << colliding << " of " << ok.size() << " |\n";
    }
  }
  return md.str();
}

namespace {

/// "Model queries, in plans on a bare model (every planner's, solved or not): METHOD N% of their
/// time, M per query (K queries); ...", or "" when no plan asked a bare model.
std::string modelQueryLine(const PlanRows& r, const RowFilter& where) {
  std::ostringstream line;
  for (const std::string& method : methodsOf(r, where)) {
    double planSeconds = 0, checkSeconds = 0;
    std::uint64_t checks = 0;
    for (const PlanRow& row : r.rows) {
      if ((where && !where(row)) || row.method != method) continue;
      planSeconds += row.outcome.modelPlanSeconds;
      checkSeconds += row.outcome.modelCheckSeconds;
      checks += row.outcome.modelChecks;
    }
    if (checks == 0 || planSeconds <= 0) continue;
    char text[160];
    std::snprintf(text, sizeof text, "%s %.0f%% of their time, %s per query (%llu queries)",
                  method.c_str(), 100 * checkSeconds / planSeconds,
                  durationText(checkSeconds / static_cast<double>(checks)).c_str(),
                  static_cast<unsigned long long>(checks));
    line << (line.tellp() > 0 ? "; " : "") << text;
  }
  if (line.tellp() == 0) return "";
  return "\nModel queries, in plans on a bare model (all of them, solved or not; the clock read "
         "around each question included): " +
         line.str() + ".\n";
}

}  // namespace

std::string timeBreakdown(const PlanRows& r, const RowFilter& where,
                          const std::vector<std::string>& planners) {
  std::ostringstream md;
  md << "| Planner | Method | Plan | of which attempts that failed | of which simplify | Their "
        "sources answering (share of the attempts' time) | Verify | Repair | Plans before "
        "verification | Their sources' checks | Exact checks | Oracle checks |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const std::string& planner : planners) {
    for (const std::string& method : methodsOf(r, where)) {
      const auto ok = select(r, where, [&](const PlanRow& row) {
        return row.planner == planner && row.method == method && row.outcome.solved;
      });
      if (ok.empty()) continue;
      const auto median = [&](auto value) { return summaryOf(ok, value).median; };
      char counts[160];
      std::snprintf(
          counts, sizeof counts, "%.1f | %.0f | %.0f | %.0f",
          median([](const PlanOutcome& o) { return static_cast<double>(o.attempts); }),
          median([](const PlanOutcome& o) { return static_cast<double>(o.planChecks); }),
          median([](const PlanOutcome& o) { return static_cast<double>(o.exactChecks); }),
          median([](const PlanOutcome& o) { return static_cast<double>(o.relaxedChecks); }));
      // The median of each plan's share, not a ratio of medians (a plan's checks and its time
      // go together).
      char checkShare[32];
      std::snprintf(checkShare, sizeof checkShare, "%.0f%%",
                    100 * median([](const PlanOutcome& o) { return o.planCheckShare; }));
      md << "| " << planner << " | " << method << " | "
         << durationText(median([](const PlanOutcome& o) { return o.planSeconds; })) << " | "
         << durationText(median([](const PlanOutcome& o) { return o.failedPlanSeconds; })) << " | "
         << durationText(median([](const PlanOutcome& o) { return o.simplifySeconds; })) << " | "
         << durationText(median([](const PlanOutcome& o) { return o.planCheckSeconds; })) << " ("
         << checkShare << ") | "
         << durationText(median([](const PlanOutcome& o) { return o.verifySeconds; })) << " | "
         << durationText(median([](const PlanOutcome& o) { return o.repairSeconds; })) << " | "
         << counts << " |\n";
    }
  }
  md << modelQueryLine(r, where);
  return md.str();
}

/// Per planner, FCL's total time over each other method's, from means and from medians over
/// solved plans.
std::string ratioLine(const PlanRows& r, const RowFilter& where,
                      const std::vector<std::string>& planners, const std::string& lead,
                      const std::function<double(const PlanRow&)>& value, bool median) {
  std::ostringstream md;
  md << lead << ":";
  for (const std::string& planner : planners) {
    const auto statistic = [&](const std::string& method) {
      std::vector<double> values;
      for (const PlanRow& row : r.rows) {
        if ((!where || where(row)) && row.planner == planner && row.method == method &&
            row.outcome.solved)
          values.push_back(value(row));
      }
      const Summary s = summarize(values);
      return median ? s.median : s.mean;
    };
    const double base = statistic("FCL");
    md << (planner == planners.front() ? " " : "; ") << planner << ":";
    for (const std::string& method : methodsOf(r, where)) {
      if (method == "FCL") continue;
      const double ratio = base / statistic(method);
      // A side that solved nothing has no time: "n/a", not "nanx" (a script reads the line).
      if (!std::isfinite(ratio)) {
        md << ' ' << method << " n/a";
        continue;
      }
      char buffer[96];
      std::snprintf(buffer, sizeof buffer, " %s %.1fx", method.c_str(), ratio);
      md << buffer;
    }
  }
  md << ".\n";
  return md.str();
}

std::string speedups(const PlanRows& r, const RowFilter& where,
                     const std::vector<std::string>& planners) {
  // Means carry the paper's comparison; medians are not swayed by the odd query that runs into
  // the time limit.
  const auto total = [](const PlanRow& row) { return row.outcome.totalSeconds; };
  return "\n" +
         ratioLine(r, where, planners,
                   "Mean total time of FCL / of each method (higher is faster than FCL)", total,
                   false) +
         ratioLine(r, where, planners,
                   "Median total time of FCL / of each method (higher is faster than FCL)", total,
                   true);
}

std::vector<std::string> plannerNames(const std::vector<PlannerType>& types) {
  std::vector<std::string> names;
  for (const PlannerType t : types) names.push_back(plannerName(t));
  return names;
}

}  // namespace fastron::experiments
