#include "fastron/planning/verify_repair.h"

#include <algorithm>
#include <string>

namespace fastron {
namespace {

using Clock = std::chrono::steady_clock;

bool contains(const std::vector<std::size_t>& sorted, std::size_t i) {
  return std::binary_search(sorted.begin(), sorted.end(), i);
}

}  // namespace

VerifiedPlan verifyAndRepair(const Path& path, const std::shared_ptr<const CollisionChecker>& exact,
                             const JointLimits& limits, const PlannerOptions& options) {
  constexpr int kRounds = 3;  // a repaired stretch is planned on the exact checker, so one suffices
  VerifiedPlan result;
  result.path = path;
  for (int round = 0; round < kRounds; ++round) {
    auto began = Clock::now();
    const PathCheck check = checkPath(*exact, result.path, options.resolution);
    result.verifyTime += Clock::now() - began;
    if (check.valid()) {
      result.status = PlanStatus::Solved;
      result.failure.clear();
      return result;
    }
    const Path& old = result.path;
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
    Path repaired{old.front()};
    std::size_t i = 0;  // the last valid waypoint kept
    while (i + 1 < old.size()) {
      if (!contains(check.invalidEdges, i) && !contains(check.invalidWaypoints, i + 1)) {
        repaired.push_back(old[++i]);
        continue;
      }
      // Excise up to the next valid waypoint and bridge the gap on the exact checker.
      std::size_t j = i + 1;
      while (contains(check.invalidWaypoints, j)) ++j;
      ++result.invalidStretches;
      // A stretch is short, so it gets a quarter of the time; a waypoint the approximate plan
      // left in a pocket of free space may have no short way out, and then the whole motion is
      // planned again on the exact checker.
      PlannerOptions stretchOptions = options;
      stretchOptions.timeLimit = options.timeLimit / 4;
      const PlanResult bridge = planMotion(exact, limits, old[i], old[j], stretchOptions);
      if (!bridge.solved()) {
        const PlanResult whole = planMotion(exact, limits, old.front(), old.back(), options);
        if (!whole.solved()) {
          result.repairTime += Clock::now() - began;
          result.status = PlanStatus::Timeout;
          result.failure = "could not replan the stretch between waypoints " + std::to_string(i) +
                           " and " + std::to_string(j) + " on " + exact->name() +
                           ", nor the whole path (" + toString(whole.status) + ")";
          return result;
        }
        repaired = whole.path;
        result.wholePathReplanned = true;
        break;
      }
      repaired.insert(repaired.end(), bridge.path.begin() + 1, bridge.path.end());
      i = j;
    }
    result.path = std::move(repaired);
    result.repairTime += Clock::now() - began;
  }
  result.status = PlanStatus::Timeout;
  result.failure = "the path still collided after " + std::to_string(kRounds) + " repair rounds";
  return result;
}

VerifiedPlan planVerified(const CollisionSource& approximate,
                          const std::shared_ptr<const CollisionChecker>& exact,
                          const JointLimits& limits, const Eigen::VectorXd& start,
                          const Eigen::VectorXd& goal, const PlannerOptions& options) {
  const PlanResult plan = planMotion(approximate, limits, start, goal, options);
  if (plan.solved()) {
    VerifiedPlan result = verifyAndRepair(plan.path, exact, limits, options);
    result.planTime = plan.time;
    return result;
  }
  // The approximate checker found no path (or thinks an end collides): plan it all exactly.
  const auto began = Clock::now();
  const PlanResult exactPlan = planMotion(exact, limits, start, goal, options);
  const auto repairTime = Clock::now() - began;
  VerifiedPlan result;
  if (exactPlan.solved()) {
    result = verifyAndRepair(exactPlan.path, exact, limits, options);  // the final check
    result.invalidStretches += 1;
  } else {
    result.status = exactPlan.status;
    result.failure = toString(exactPlan.status) + " under " + exact->name();
  }
  result.planTime = plan.time;
  result.repairTime += repairTime;
  result.wholePathReplanned = true;
  return result;
}

}  // namespace fastron
