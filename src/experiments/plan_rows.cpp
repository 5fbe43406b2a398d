#include "plan_rows.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>

#include "fastron/core/active_learning.h"
#include "fastron/core/hybrid_checker.h"
#include "fastron/planning/motion.h"

namespace fastron::experiments {
namespace {

const std::vector<std::string> kPlanColumns{
    "solved",   "status",     "plan_s",       "simplify_s",  "verify_s",
    "repair_s", "total_s",    "path_length",  "waypoints",   "stretches",
    "fallback", "exact_ends", "collides_fcl", "exact_share", "planned_on"};

}  // namespace

std::vector<std::string> columnsWith(std::vector<std::string> first,
                                     const std::vector<std::string>& last) {
  first.insert(first.end(), kPlanColumns.begin(), kPlanColumns.end());
  first.insert(first.end(), last.begin(), last.end());
  return first;
}

/// The plan's cells of a result row; `audit` is an FCL checker the planner never used.
std::vector<std::string> planCells(const MethodPlan& method, const CollisionChecker& audit,
                                   double resolution) {
  const VerifiedPlan& plan = method.plan;
  const bool solved = plan.solved();
  const double collides =
      solved ? (checkPath(audit, plan.path, resolution).valid() ? 0.0 : 1.0) : std::nan("");
  return {solved ? "1" : "0",
          plan.failure.empty() ? toString(plan.status) : plan.failure,
          cell(seconds(plan.planTime)),
          cell(seconds(plan.simplifyTime)),
          cell(seconds(plan.verifyTime)),
          cell(seconds(plan.repairTime)),
          cell(seconds(plan.totalTime())),
          cell(solved ? pathLength(plan.path) : std::nan("")),
          std::to_string(plan.path.size()),
          std::to_string(plan.invalidStretches),
          plan.wholePathReplanned ? "1" : "0",
          plan.substituteEnds ? "1" : "0",
          cell(collides),
          cell(method.exactShare),
          plan.plannedOn};
}

std::vector<std::string> joined(std::vector<std::string> first,
                                const std::vector<std::string>& last) {
  first.insert(first.end(), last.begin(), last.end());
  return first;
}

/// Fastron, Hybrid (Fastron with FCL inside the model's calibrated band) and GJK, each verified
/// and repaired with FCL, and FCL itself, on one query. Hybrid only when the band was calibrated.
std::vector<MethodPlan> planWithEachChecker(const CalibratedModel& model, const CheckerPtr& gjk,
                                            const CheckerPtr& fcl, const JointLimits& limits,
                                            const Eigen::VectorXd& start,
                                            const Eigen::VectorXd& goal,
                                            const PlannerOptions& options, std::size_t turn) {
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
  // between): always FCL last gave FCL BIT* plans 1.5-2 times faster than first did.
  std::vector<MethodPlan> plans(methods.size());
  for (std::size_t k = 0; k < methods.size(); ++k) {
    const std::size_t m = (turn + k) % methods.size();
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

/// Start and goal on opposite sides of the workspace: the first joint (the shoulder's yaw) in
/// the lowest and the highest 30% of its range, the others uniform; both free under `fcl`.
std::pair<Eigen::VectorXd, Eigen::VectorXd> oppositeEnds(const JointLimits& limits,
                                                         const CollisionChecker& fcl, Rng& rng) {
  const double lo = limits.lower()[0], hi = limits.upper()[0], band = 0.3 * (hi - lo);
  std::uniform_real_distribution<double> u(0.0, band);
  Eigen::VectorXd start = sampleFree(
      fcl,
      [&] {
        Eigen::VectorXd q = uniformIn(limits, rng);
        q[0] = lo + u(rng);
        return q;
      },
      "start");
  Eigen::VectorXd goal = sampleFree(
      fcl,
      [&] {
        Eigen::VectorXd q = uniformIn(limits, rng);
        q[0] = hi - u(rng);
        return q;
      },
      "goal");
  if (std::uniform_int_distribution<int>(0, 1)(rng) == 1) std::swap(start, goal);
  return {start, goal};
}

std::string progressLine(const std::string& what, std::size_t i, std::size_t n) {
  return what + " " + std::to_string(i + 1) + "/" + std::to_string(n);
}

/// The Markdown table of plan results of the rows matching `where`, one line per (planner,
/// method): success rate, then means ± std over solved plans.
std::string planTable(const Table& r, const Table::Filter& where,
                      const std::vector<std::string>& planners) {
  std::ostringstream md;
  md << "| Planner | Method | Success | Plan (of which simplify) | Verify | Repair | Total | Path "
        "length (joint space) | Repaired stretches | Plans repaired | Plan queries FCL answered | "
        "Final paths colliding (FCL) |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const std::string& planner : planners) {
    for (const std::string& method : r.distinct("method", where)) {
      Table::Filter all = where;
      all.emplace_back("planner", planner);
      all.emplace_back("method", method);
      const std::vector<double> solved = r.numbers("solved", all);
      if (solved.empty()) continue;
      Table::Filter ok = all;
      ok.emplace_back("solved", "1");
      const auto stat = [&](const char* column) { return summarize(r.numbers(column, ok)); };
      const auto solvedCount =
          static_cast<std::size_t>(std::count(solved.begin(), solved.end(), 1.0));
      const std::vector<double> collides = r.numbers("collides_fcl", ok);
      const auto colliding =
          static_cast<std::size_t>(std::count(collides.begin(), collides.end(), 1.0));
      char rate[64];
      std::snprintf(rate, sizeof rate, "%.2f (%zu/%zu)",
                    static_cast<double>(solvedCount) / static_cast<double>(solved.size()),
                    solvedCount, solved.size());
      const std::vector<double> stretches = r.numbers("stretches", ok);
      const auto repaired =
          std::count_if(stretches.begin(), stretches.end(), [](double s) { return s > 0; });
      char repairedShare[64];
      std::snprintf(repairedShare, sizeof repairedShare, "%.0f%%",
                    stretches.empty() ? 0.0
                                      : 100.0 * static_cast<double>(repaired) /
                                            static_cast<double>(stretches.size()));
      md << "| " << planner << " | " << method << " | " << rate << " | "
         << durationMeanStd(stat("plan_s")) << " (" << durationMeanStd(stat("simplify_s")) << ") | "
         << durationMeanStd(stat("verify_s")) << " | " << durationMeanStd(stat("repair_s")) << " | "
         << durationMeanStd(stat("total_s")) << " | " << meanStd(stat("path_length"), 2) << " | "
         << meanStd(stat("stretches"), 2) << " | " << repairedShare << " | "
         << meanStd(summarize(r.numbers("exact_share", all)), 3) << " | " << colliding << " of "
         << collides.size() << " |\n";
    }
  }
  return md.str();
}

/// Per planner, FCL's total time over each other method's, from means and from medians over
/// solved plans.
std::string speedups(const Table& r, const Table::Filter& where,
                     const std::vector<std::string>& planners) {
  std::ostringstream md;
  // Means carry the paper's comparison; medians are not swayed by the odd query that runs into
  // the time limit.
  for (const bool median : {false, true}) {
    md << (median ? "Median" : "\nMean")
       << " total time of FCL / of each method (higher is faster than FCL):";
    for (const std::string& planner : planners) {
      const auto statistic = [&](const std::string& method) {
        Table::Filter filter = where;
        filter.emplace_back("planner", planner);
        filter.emplace_back("method", method);
        filter.emplace_back("solved", "1");
        const Summary s = summarize(r.numbers("total_s", filter));
        return median ? s.median : s.mean;
      };
      const double base = statistic("FCL");
      md << (planner == planners.front() ? " " : "; ") << planner << ":";
      for (const std::string& method : r.distinct("method", where)) {
        if (method == "FCL") continue;
        char buffer[64];
        std::snprintf(buffer, sizeof buffer, " %s %.1fx", method.c_str(), base / statistic(method));
        md << buffer;
      }
    }
    md << ".\n";
  }
  return md.str();
}

std::vector<std::string> plannerNames(const std::vector<PlannerType>& types) {
  std::vector<std::string> names;
  for (const PlannerType t : types) names.push_back(plannerName(t));
  return names;
}

}  // namespace fastron::experiments
