#include "fastron/planning/planner.h"

#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/tools/config/MagicConstants.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <string>

#include "fastron/core/error.h"

namespace fastron {
namespace og = ompl::geometric;
namespace ob = ompl::base;

std::string plannerName(PlannerType type) {
  switch (type) {
    case PlannerType::Rrt:
      return "RRT";
    case PlannerType::RrtConnect:
      return "RRTConnect";
    case PlannerType::RrtStar:
      return "RRT*";
    case PlannerType::BitStar:
      return "BIT*";
  }
  return "?";
}

PlannerType parsePlannerType(std::string_view name) {
  std::string key;
  for (const char c : name) {
    if (c != '-' && c != '_') key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (key == "rrt") return PlannerType::Rrt;
  if (key == "rrtconnect") return PlannerType::RrtConnect;
  if (key == "rrt*" || key == "rrtstar") return PlannerType::RrtStar;
  if (key == "bit*" || key == "bitstar") return PlannerType::BitStar;
  throw InvalidArgument("unknown planner '" + std::string(name) +
                        "' (choose RRT, RRTConnect, RRT* or BIT*)");
}

std::string simplificationName(PathSimplification simplification) {
  return simplification == PathSimplification::Full ? "full" : "shortcuts";
}

PathSimplification parsePathSimplification(std::string_view name) {
  std::string key;
  for (const char c : name) key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (key == "full") return PathSimplification::Full;
  if (key == "shortcuts") return PathSimplification::Shortcuts;
  throw InvalidArgument("unknown path simplification '" + std::string(name) +
                        "' (choose full or shortcuts)");
}

std::vector<PlannerType> allPlannerTypes() {
  return {PlannerType::Rrt, PlannerType::RrtConnect, PlannerType::RrtStar, PlannerType::BitStar};
}

void validate(const PlannerOptions& options) {
  if (!(options.range >= 0) || !std::isfinite(options.range)) {
    throw InvalidArgument("planner range must be 0 (OMPL's default) or positive, got " +
                          std::to_string(options.range));
  }
  if (options.rangeHalvings > kMaxRangeHalvings) {
    throw InvalidArgument("rangeHalvings must be at most " + std::to_string(kMaxRangeHalvings) +
                          ", got " + std::to_string(options.rangeHalvings));
  }
  if (!(options.verify.hybridRange >= 0) || !std::isfinite(options.verify.hybridRange)) {
    throw InvalidArgument("hybridRange must be 0 (half the planner's range) or positive, got " +
                          std::to_string(options.verify.hybridRange));
  }
  if (!(options.resolution > 0) || !std::isfinite(options.resolution)) {
    throw InvalidArgument("motion resolution must be positive, got " +
                          std::to_string(options.resolution));
  }
  if (!(options.modelResolution >= 0) || !std::isfinite(options.modelResolution)) {
    throw InvalidArgument("model resolution must be 0 (" + std::to_string(kModelStepsPerStep) +
                          " times the resolution) or positive, got " +
                          std::to_string(options.modelResolution));
  }
  if (!(options.timeLimit > 0) || !std::isfinite(options.timeLimit)) {
    throw InvalidArgument("planning time limit must be positive, got " +
                          std::to_string(options.timeLimit));
  }
  if (!(options.verify.stretchShare > 0) || !(options.verify.stretchShare <= 1)) {
    throw InvalidArgument("stretchShare must be in (0, 1], got " +
                          std::to_string(options.verify.stretchShare));
  }
  if (!(options.verify.bridgeMargin >= 0) || !std::isfinite(options.verify.bridgeMargin)) {
    throw InvalidArgument("bridgeMargin must be finite and >= 0, got " +
                          std::to_string(options.verify.bridgeMargin));
  }
  if (!(options.verify.approximateShare > 0) || !(options.verify.approximateShare <= 1)) {
    throw InvalidArgument("approximateShare must be in (0, 1], got " +
                          std::to_string(options.verify.approximateShare));
  }
  if (!(options.verify.modelShare > 0) || !(options.verify.modelShare <= 1)) {
    throw InvalidArgument("modelShare must be in (0, 1], got " +
                          std::to_string(options.verify.modelShare));
  }
  if (!(options.verify.substituteShare > 0) || !(options.verify.substituteShare <= 1)) {
    throw InvalidArgument("substituteShare must be in (0, 1], got " +
                          std::to_string(options.verify.substituteShare));
  }
  if (!(options.simplifyTime >= 0) || !std::isfinite(options.simplifyTime)) {
    throw InvalidArgument("path simplification time must be 0 (off) or positive, got " +
                          std::to_string(options.simplifyTime));
  }
}

void seedPlanners(std::uint64_t seed, std::uint64_t query) {
  // splitmix64 of both: OMPL takes a non-zero 32-bit seed.
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ULL + query + 1;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  // OMPL logs an error when it re-seeds after its first generators; silenced, since library code
  // does not print and re-seeding is the point.
  const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(z >> 32) | 1U);
  ompl::msg::setLogLevel(level);
}

namespace {

/// The range of an RRT, RRT-Connect or RRT* planner; 0 for another.
double rangeOf(const ob::Planner& planner) {
  if (const auto* p = dynamic_cast<const og::RRTConnect*>(&planner)) return p->getRange();
  if (const auto* p = dynamic_cast<const og::RRT*>(&planner)) return p->getRange();
  if (const auto* p = dynamic_cast<const og::RRTstar*>(&planner)) return p->getRange();
  return 0;
}

bool answersFromAModel(const CollisionSource& source) {
  const auto* checker = std::get_if<std::shared_ptr<const CollisionChecker>>(&source);
  return checker == nullptr || (*checker != nullptr && (*checker)->answersFromAModel());
}

}  // namespace

ob::PlannerPtr makePlanner(const ob::SpaceInformationPtr& si, const PlannerOptions& options) {
  validate(options);
  switch (options.type) {
    case PlannerType::Rrt: {
      auto planner = std::make_shared<og::RRT>(si);
      if (options.range > 0) planner->setRange(options.range);
      return planner;
    }
    case PlannerType::RrtConnect: {
      auto planner = std::make_shared<RrtConnectTrees>(si);
      if (options.range > 0) planner->setRange(options.range);
      return planner;
    }
    case PlannerType::RrtStar: {
      // RRT* stops at its first solution only through the objective's cost threshold; see
      // makeProblemDefinition().
      auto planner = std::make_shared<og::RRTstar>(si);
      if (options.range > 0) planner->setRange(options.range);
      return planner;
    }
    case PlannerType::BitStar: {
      auto planner = std::make_shared<og::BITstar>(si);
      planner->setStopOnSolnImprovement(true);
      return planner;
    }
  }
  throw InvalidArgument("unknown planner type");
}

std::string_view toString(PlanStatus status) {
  switch (status) {
    case PlanStatus::Solved:
      return "solved";
    case PlanStatus::InvalidStart:
      return "start in collision";
    case PlanStatus::InvalidGoal:
      return "goal in collision";
    case PlanStatus::Timeout:
      return "no path within the time limit";
  }
  return "?";
}

namespace {

void checkEndpoint(const Eigen::VectorXd& q, const JointLimits& limits, const char* what) {
  checkConfiguration(std::span<const double>(q.data(), static_cast<std::size_t>(q.size())),
                     limits.dim(), what);
  for (Eigen::Index j = 0; j < q.size(); ++j) {
    if (q[j] < limits.lower()[j] || q[j] > limits.upper()[j]) {
      throw InvalidArgument(std::string(what) + " value [" + std::to_string(j) +
                            "] = " + std::to_string(q[j]) + " is outside the joint limits [" +
                            std::to_string(limits.lower()[j]) + ", " +
                            std::to_string(limits.upper()[j]) + "]");
    }
  }
}

ob::ScopedState<> stateOf(const ob::SpaceInformationPtr& si, const Eigen::VectorXd& q) {
  ob::ScopedState<> state(si->getStateSpace());
  for (Eigen::Index j = 0; j < q.size(); ++j) state[static_cast<unsigned>(j)] = q[j];
  return state;
}

}  // namespace

ob::ProblemDefinitionPtr makeProblemDefinition(const ob::SpaceInformationPtr& si,
                                               const Eigen::VectorXd& start,
                                               const Eigen::VectorXd& goal, PlannerType type) {
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  problem->setStartAndGoalStates(stateOf(si, start), stateOf(si, goal));
  if (type == PlannerType::RrtStar || type == PlannerType::BitStar) {
    auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
    // Any path satisfies an infinite threshold, so RRT* ends its loop at the first solution.
    objective->setCostThreshold(objective->infiniteCost());
    problem->setOptimizationObjective(objective);
  }
  return problem;
}

RangeSchedule::RangeSchedule(ob::Planner& planner, const PlannerOptions& options)
    : planner_(options.rangeStage == 0 || options.rangeHalvings == 0
                   ? nullptr
                   : dynamic_cast<RrtConnectTrees*>(&planner)),
      stage_(options.rangeStage),
      halvings_(options.rangeHalvings),
      longest_(planner_ != nullptr ? planner_->getRange() : 0) {}

void RangeSchedule::endRound() {
  const std::size_t start = planner_->startTreeSize(), goal = planner_->goalTreeSize();
  const bool startSmaller = start < goal;
  const std::size_t smaller = std::min(start, goal), larger = std::max(start, goal);
  const std::size_t gained = startSmaller ? start - startAtRound_ : goal - goalAtRound_;
  if (smaller * kPocketSizeRatio < larger && gained * kPocketIterationsPerNode < roundIterations_) {
    pocket_ = startSmaller ? PocketTree::Start : PocketTree::Goal;
  }
  startAtRound_ = start;
  goalAtRound_ = goal;
  roundIterations_ = 0;
}

ob::PlannerStatus RangeSchedule::solve(ob::Planner& planner,
                                       const ob::PlannerTerminationCondition& stop) {
  if (planner_ == nullptr) return planner.solve(stop);
  // Stages stop growing at 2^30 times the first: no time limit lasts that many iterations, and
  // the shift stays defined.
  constexpr unsigned kMaxRounds = 30;
  for (;;) {
    std::size_t iterations = 0;
    bool stageOver = false;
    // Evaluated once per iteration, after `stop` (which may count iterations itself), before the
    // iteration: the `iterations`-th of this solve() grows the start tree when odd.
    const ob::PlannerStatus status = planner.solve(ob::plannerOrTerminationCondition(
        stop, ob::PlannerTerminationCondition([&] {
          stageOver = ++iterations > (stage_ << std::min(rounds_, kMaxRounds));
          if (pocket_ != PocketTree::None && !stageOver) {
            const PocketTree grows = iterations % 2 == 1 ? PocketTree::Start : PocketTree::Goal;
            const unsigned step = grows == pocket_ ? halvings_ + 1 : step_;
            planner_->setRange(std::ldexp(longest_, -static_cast<int>(step)));
          }
          return stageOver;
        })));
    if (!stageOver || status == ob::PlannerStatus::EXACT_SOLUTION) return status;
    roundIterations_ += iterations - 1;  // the last evaluation ended the stage
    if (step_ == halvings_) {
      ++rounds_;
      if (pocket_ == PocketTree::None) endRound();
    }
    step_ = step_ == halvings_ ? 0 : step_ + 1;
    planner_->setRange(std::ldexp(longest_, -static_cast<int>(step_)));
  }
}

std::string describeRange(const PlannerOptions& options, const std::string& unit) {
  std::ostringstream text;
  if (options.range > 0) {
    text << options.range << ' ' << unit;
  } else {
    text << "OMPL's default";
  }
  if (options.rangeStage == 0 || options.rangeHalvings == 0) return text.str();
  text << ", halved after " << options.rangeStage << " iterations without a path down to 1/"
       << (1U << options.rangeHalvings)
       << " of it, then again from it, each round twice as long as the one before; a tree in a "
          "pocket grows at 1/"
       << (1U << (options.rangeHalvings + 1)) << " of it";
  return text.str();
}

double edgeResolution(const CollisionSource& source, const PlannerOptions& options) {
  return answersFromAModel(source) ? modelStep(options) : options.resolution;
}

double optimisticHybridRange(const PlannerOptions& options, const JointLimits& limits) {
  if (options.verify.hybridRange > 0) return options.verify.hybridRange;
  // OMPL's default: this fraction of the space's maximum extent, for a real vector space the
  // diagonal of its bounds.
  const double range = options.range > 0 ? options.range
                                         : ompl::magic::MAX_MOTION_LENGTH_AS_SPACE_EXTENT_FRACTION *
                                               (limits.upper() - limits.lower()).norm();
  return 0.5 * range;
}

double modelStep(const PlannerOptions& options) {
  return options.modelResolution > 0 ? options.modelResolution
                                     : kModelStepsPerStep * options.resolution;
}

namespace {

/// Simplifies `path` within options.simplifyTime, as options.simplification says.
void simplifyPath(const ob::SpaceInformationPtr& si, og::PathGeometric& path,
                  const PlannerOptions& options) {
  og::PathSimplifier simplifier(si);
  const auto timeLeft = ob::timedPlannerTerminationCondition(options.simplifyTime);
  // One simplification of `path`; false when it ends with an edge through an obstacle.
  const auto simplify = [&] {
    if (options.simplification == PathSimplification::Full)
      return simplifier.simplify(path, timeLeft);
    // As simplify's first round, without the smoothing: passes until one gains nothing or the
    // time is up (the first always runs, as simplify's first round does). A shortcut may start
    // at a point between two checked states of an edge, unchecked itself (a corner the edge
    // grazes): checkAndRepair moves such states out, as simplify does after its passes.
    for (int pass = 0; pass < 5 && simplifier.shortcutPath(path) && !timeLeft(); ++pass) {
    }
    for (int pass = 0; pass < 5 && simplifier.reduceVertices(path) && !timeLeft(); ++pass) {
    }
    simplifier.collapseCloseVertices(path);
    return path.checkAndRepair(ompl::magic::MAX_VALID_SAMPLE_ATTEMPTS).second;
  };
  // checkAndRepair (which simplify ends with too) may fail to move a state out and leave an
  // edge through an obstacle: about 1 in 1000 plans around the wall of the tests
  // (ASimplificationThatEndsInvalidKeepsThePlannersPath). The planner's path, every edge of it
  // checked, is simplified again (shortcuts are random) while time is left, else returned.
  const og::PathGeometric planned(path);
  for (int attempt = 0; !simplify(); ++attempt) {
    path = planned;
    if (attempt == 2 || timeLeft()) break;
  }
}

}  // namespace

PlanResult planMotion(const CollisionSource& source, const JointLimits& limits,
                      const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                      const PlannerOptions& options) {
  validate(options);
  checkEndpoint(start, limits, "start");
  checkEndpoint(goal, limits, "goal");
  const auto began = std::chrono::steady_clock::now();
  const auto si = makeSpaceInformation(source, limits, edgeResolution(source, options));
  PlanResult result;
  SourceUseCounter ends;  // the planner's own questions are counted by si's adapters
  const auto finish = [&](PlanStatus status) {
    result.status = status;
    result.time = std::chrono::steady_clock::now() - began;
    const SourceUse planner = sourceUse(si), asked = ends.total();
    result.checks = asked.answered + planner.answered;
    result.checkTime = asked.time + planner.time;
    return result;
  };
  const auto collides = [&](const Eigen::VectorXd& end) {
    return firstCollision(source, end.data(), 1, limits.dim(), ends) == 0;
  };
  if (collides(start)) return finish(PlanStatus::InvalidStart);
  if (collides(goal)) return finish(PlanStatus::InvalidGoal);

  const auto planner = makePlanner(si, options);
  planner->setProblemDefinition(makeProblemDefinition(si, start, goal, options.type));
  planner->setup();
  // Not solve(double): that checks the time on a helper thread, started and joined per query.
  ob::PlannerTerminationCondition stop = ob::timedPlannerTerminationCondition(options.timeLimit);
  // Not on a model: its plan is time-boxed and stops at an end it encloses (below), which
  // long edges' failed extensions would hide until the shortest range.
  const bool onAModel = std::holds_alternative<std::shared_ptr<const Model>>(source);
  PlannerOptions scheduled = options;
  if (onAModel) scheduled.rangeStage = 0;
  RangeSchedule schedule(*planner, scheduled);
  std::size_t iterations = 0;
  // Only on a model: an exact checker's pocket may have a narrow way out that a few hundred
  // random directions miss, and a plan on a hybrid is the last before the exact checker.
  const auto* rrtConnect = options.enclosedAfter > 0 && onAModel
                               ? dynamic_cast<const RrtConnectTrees*>(planner.get())
                               : nullptr;
  if (rrtConnect != nullptr) {
    // Evaluated once per iteration of RRT-Connect's loop.
    stop = ob::plannerOrTerminationCondition(
        stop, ob::PlannerTerminationCondition([&iterations, rrtConnect, &options] {
          return ++iterations > options.enclosedAfter &&
                 std::min(rrtConnect->startTreeSize(), rrtConnect->goalTreeSize()) <= 1;
        }));
  }
  const ob::PlannerStatus status = schedule.solve(*planner, stop);
  result.range = rangeOf(*planner);
  const auto problem = planner->getProblemDefinition();
  if (status != ob::PlannerStatus::EXACT_SOLUTION || !problem->hasExactSolution()) {
    return finish(PlanStatus::Timeout);
  }
  auto& path = *problem->getSolutionPath()->as<og::PathGeometric>();
  if (options.simplifyTime > 0) {
    const auto simplifyBegan = std::chrono::steady_clock::now();
    simplifyPath(si, path, options);
    result.simplifyTime = std::chrono::steady_clock::now() - simplifyBegan;
  }
  const auto dim = static_cast<Eigen::Index>(limits.dim());
  for (const ob::State* state : path.getStates()) {
    const double* values = state->as<ob::RealVectorStateSpace::StateType>()->values;
    result.path.emplace_back(Eigen::Map<const Eigen::VectorXd>(values, dim));
  }
  return finish(PlanStatus::Solved);
}

}  // namespace fastron
