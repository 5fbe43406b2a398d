#pragma once
// The planners of the paper's experiments (RRT, RRT-Connect, RRT*, BIT*), each stopping at its
// first solution, and one planning query from start to goal.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <ompl/base/Planner.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include "fastron/core/export.h"
#include "fastron/planning/motion.h"
#include "fastron/planning/ompl_adapters.h"

namespace FASTRON_API fastron {

enum class PlannerType { Rrt, RrtConnect, RrtStar, BitStar };

/// "RRT", "RRTConnect", "RRT*", "BIT*".
std::string plannerName(PlannerType type);
/// Reads those names (case-insensitive; "rrtstar", "bitstar", "rrt-connect" also accepted);
/// throws InvalidArgument naming the value and the choices.
PlannerType parsePlannerType(std::string_view name);
/// Every planner type, in the paper's order.
std::vector<PlannerType> allPlannerTypes();

/// How a plan's path is shortened (PlannerOptions::simplification).
enum class PathSimplification : std::uint8_t {
  /// OMPL's PathSimplifier::simplify: shortcutting, B-spline smoothing, vertex reduction and the
  /// collapse of close vertices, in rounds within simplifyTime, as MoveIt does.
  Full,
  /// Up to five passes each of OMPL's shortcutPath and reduceVertices (fewer when one gains
  /// nothing or simplifyTime is up), then collapseCloseVertices and checkAndRepair, as simplify
  /// ends: no B-spline smoothing, whose subdivided states make most of the checks. Repairs use it
  /// for their bridges (docs/log/2026-11-28-lighter-bridges.md, "Lighter bridges").
  Shortcuts,
};

/// "full", "shortcuts".
std::string simplificationName(PathSimplification simplification);
/// Reads those names (case-insensitive); throws InvalidArgument naming the value and the choices.
PathSimplification parsePathSimplification(std::string_view name);

/// The settings of the recipes around a planner: verify and repair (planVerified,
/// verifyAndRepair) and learning within a query (planVerifiedLearning). Why each default:
/// docs/planning.md, "The settings of verify and repair, and why".
struct VerifyRepairOptions {
  /// planVerified: the share of timeLimit that planning on the approximate source, and then on
  /// its hybrid, may each take before the motion is planned on the exact checker instead
  /// (planVerifiedLearning: its hybrid's share).
  double approximateShare = 0.1;
  /// planVerifiedLearning: the share of timeLimit that its first plan on the model alone may take
  /// before a hybrid that asks the exact checker about every "collides" plans instead.
  double modelShare = 0.005;
  /// planVerified, planVerifiedLearning: the share of timeLimit (at most the plan's own share) that
  /// a plan on an approximate source between substitute ends may take, when the source called the
  /// start or the goal colliding and the exact checker finds it free.
  double substituteShare = 0.002;
  /// verifyAndRepair: the share of timeLimit that replanning one invalid stretch may take before
  /// the whole motion is planned on the exact checker instead.
  double stretchShare = 0.02;
  /// verifyAndRepair: a stretch's bridge is searched first within the box its two ends span,
  /// grown by this much (joint units) on every side, then within the joint limits. A wide box
  /// leaves room for the detours of a robot that folds onto itself (an arm of ±2π joints whose
  /// wrist meets its forearm); a narrow one keeps the planner near an obstacle's graze.
  double bridgeMargin = 1.0;
  /// planVerifiedLearning: how many times a model whose path verification finds colliding learns
  /// the exact answers it got wrong and plans again, before its last path is repaired (0: repair
  /// at once).
  unsigned learningRounds = 0;
  /// planVerifiedLearning: the proxy's oracle never says "collides" where the exact checker finds
  /// the robot free (FCL without self-collision under a model of the obstacles alone, when
  /// `exact` adds self-collision), so it may answer where verification catches a wrong "free"
  /// later: the optimistic hybrid asks it about the model's "collides", and the first repair
  /// round plans its bridges on it. Any other oracle could close what the exact checker leaves
  /// open.
  bool oracleRelaxesExact = false;
  /// planVerifiedLearning: before a colliding stretch is replanned, the model learns the exact
  /// answers it got wrong, pushes the stretch out along its collision cost's gradient
  /// (optimizeTrajectory, gradientRepairOptions) and the result is kept when the exact checker
  /// finds it free (docs/planning.md, "Gradient repair").
  bool gradientRepair = false;
  /// planVerifiedLearning: the longest tree edge (joint units) of its optimistic hybrid's plan
  /// to begin with; 0: half the planner's range (optimisticHybridRange), its schedule then
  /// ending at the planner's shortest range (one halving fewer).
  double hybridRange = 0;
};

/// The most PlannerOptions::rangeHalvings accepts: a range 2^-20 of OMPL's default is shorter
/// than any motion resolution.
inline constexpr unsigned kMaxRangeHalvings = 20;

struct PlannerOptions {
  // The planner's own settings.
  PlannerType type = PlannerType::RrtConnect;
  /// Longest tree edge (joint units) to begin with; 0: OMPL's default (a fifth of the diagonal
  /// of the joint limits' box). RRT-Connect on a checker shortens it on a schedule
  /// (RangeSchedule); on a Fastron model it stays (that plan is time-boxed and stops at an end the
  /// model encloses, which failed long extensions would hide until the shortest range).
  double range = 0;
  /// RRT-Connect on a checker: iterations without a path before its range is halved, in the
  /// first round of ranges; twice as many in each round after (0: the range stays). Long edges find
  /// paths in open space at once; among obstacles, and in many joints where a long edge moves every
  /// link at once, most of them collide (docs/planning.md, "The planner's range").
  std::size_t rangeStage = 100;
  unsigned rangeHalvings = 3;  ///< the shortest range is the first over 2^rangeHalvings
  double resolution = 0.02;    ///< longest step between checked states of an edge (joint units)
  /// The same step when planning on a Fastron model or a checker that answers from one
  /// (answersFromAModel); 0: kModelStepsPerStep times `resolution`. A path planned on a model is
  /// verified at `resolution` with the exact checker, so final paths keep that guarantee.
  double modelResolution = 0;
  double timeLimit = 10;  ///< seconds per planning query
  /// Seconds at most spent shortening a solution with OMPL's PathSimplifier (every change checked
  /// with the same collision source as the plan), as MoveIt does; 0 keeps the planner's path as
  /// found (the paper's setting).
  double simplifyTime = 0.1;
  /// How simplifyTime shortens the path. Repairs plan their bridges with Shortcuts whatever this
  /// says.
  PathSimplification simplification = PathSimplification::Full;
  /// RRT-Connect on a Fastron model (a CollisionSource holding the Model; never on a checker,
  /// hybrids included): the plan stops, as a timeout, when after this many iterations its start or
  /// goal tree still holds only its root (an end the model closed a pocket around). 0: never.
  std::size_t enclosedAfter = 256;

  /// How the recipes around the planner share the time limit, repair and learn.
  VerifyRepairOptions verify;
};

/// OMPL's RRT-Connect as makePlanner makes it, with its two trees' sizes in view (RangeSchedule,
/// and planMotion's rule for an end a model encloses).
class RrtConnectTrees : public ompl::geometric::RRTConnect {
 public:
  using ompl::geometric::RRTConnect::RRTConnect;
  /// Nodes of the tree grown from the start, and from the goal (0 before the first solve()).
  std::size_t startTreeSize() const { return tStart_ ? tStart_->size() : 0; }
  std::size_t goalTreeSize() const { return tGoal_ ? tGoal_->size() : 0; }
};

/// A tree of RRT-Connect in a pocket (RangeSchedule::pocket).
enum class PocketTree : std::uint8_t { None, Start, Goal };

/// RRT-Connect's range schedule (planMotion's): its range R (PlannerOptions::range or OMPL's
/// default), then R/2, ..., R/2^rangeHalvings, each for rangeStage iterations without a path,
/// then R again, each round of ranges twice as long per range as the one before. The trees grown
/// so far stay (a second solve() goes on from them, their edges checked already), so a stage adds
/// to the search of the ones before. Every range gets the same share of the iterations: Baxter's
/// two arms need the shortest, one of the Panda's bookshelf problems the longest
/// (docs/log/2026-11-29-the-planners-range.md).
///
/// A tree in a pocket: when a round ends with one tree holding under 1/kPocketSizeRatio of the
/// other's nodes and having gained under one node per kPocketIterationsPerNode of the round's
/// iterations, its end is enclosed (every extension from it collides, at every range of the
/// schedule: Baxter's two arms reaching into a shelf). From then on that tree grows at half the
/// shortest range, R/2^(rangeHalvings+1), while the other keeps the schedule (whose long edges
/// are what reaches into some pockets: one range for both trees lost the mobile arm's box
/// problems). RRT-Connect grows its two trees in turn, the start tree first in every solve(), and
/// the range is set before each of its iterations (docs/log/2026-12-02-a-tree-in-a-pocket.md).
///
/// For another planner than makePlanner's RRT-Connect, or rangeStage 0, the range stays. Set up
/// the planner before constructing it (its range is read then).
class RangeSchedule {
 public:
  RangeSchedule(ompl::base::Planner& planner, const PlannerOptions& options);
  /// planner.solve(stop), on the schedule: `stop` is also evaluated once per iteration.
  ompl::base::PlannerStatus solve(ompl::base::Planner& planner,
                                  const ompl::base::PlannerTerminationCondition& stop);
  /// The tree found in a pocket so far, if any.
  PocketTree pocket() const { return pocket_; }

  static constexpr std::size_t kPocketSizeRatio = 16;
  static constexpr std::size_t kPocketIterationsPerNode = 500;

 private:
  /// At the end of a round: finds a tree in a pocket.
  void endRound();

  RrtConnectTrees* planner_;  ///< null: the range stays
  std::size_t stage_;
  unsigned halvings_;
  double longest_;
  unsigned step_ = 0;    ///< the range is longest_ / 2^step_
  unsigned rounds_ = 0;  ///< rounds of every range done: a stage is rangeStage 2^rounds_
  PocketTree pocket_ = PocketTree::None;
  std::size_t roundIterations_ = 0;                 ///< iterations of the round so far
  std::size_t startAtRound_ = 0, goalAtRound_ = 0;  ///< the trees' sizes as the round began
};

/// For reports: "1.5 UNIT" or "OMPL's default", then the schedule (", halved after 100
/// iterations without a path, ...").
std::string describeRange(const PlannerOptions& options, const std::string& unit);

/// The default model step, in steps of the exact checker (PlannerOptions::modelResolution).
inline constexpr double kModelStepsPerStep = 3;

/// Throws InvalidArgument naming the field when an option is out of range.
void validate(const PlannerOptions& options);

/// PlannerOptions::modelResolution, or kModelStepsPerStep times the resolution when it is 0.
double modelStep(const PlannerOptions& options);

/// The range of planVerifiedLearning's optimistic hybrid: options.hybridRange, or half of
/// options.range, or, when both are 0, half of OMPL's default range (a fifth of the diagonal of
/// the joint limits' box), i.e. a tenth of that diagonal (1.3 rad on the Panda).
double optimisticHybridRange(const PlannerOptions& options, const JointLimits& limits);

/// The step at which planning on `source` checks edges: options.resolution for an exact checker,
/// the model step (PlannerOptions::modelResolution) for a model or a checker answering from one.
double edgeResolution(const CollisionSource& source, const PlannerOptions& options);

/// Seeds OMPL's generator of seeds (ompl::RNG::setSeed, process-wide) from a run's seed and a
/// query's index, so that the planners and simplifiers made next draw the same random numbers in
/// every run: a plan whose checker gives the same answers is then the same plan (unless a time
/// limit cuts it short). OMPL's error about re-seeding after its first generators is silenced.
void seedPlanners(std::uint64_t seed, std::uint64_t query);

/// A planner of the given type on `si`; with a problem from makeProblemDefinition it stops at its
/// first solution (BIT*: stop-on-solution-improvement is set here).
ompl::base::PlannerPtr makePlanner(const ompl::base::SpaceInformationPtr& si,
                                   const PlannerOptions& options);

/// The query from start to goal for a planner of `type`. RRT* and BIT* get the path-length
/// objective with its cost threshold at infinite cost: any solution satisfies it, so RRT* ends its
/// loop at the first one (OMPL's exactSolnPlannerTerminationCondition does not stop it).
ompl::base::ProblemDefinitionPtr makeProblemDefinition(const ompl::base::SpaceInformationPtr& si,
                                                       const Eigen::VectorXd& start,
                                                       const Eigen::VectorXd& goal,
                                                       PlannerType type);

enum class PlanStatus {
  Solved,        ///< a path from start to goal
  InvalidStart,  ///< the start configuration collides (under the checker used)
  InvalidGoal,   ///< the goal configuration collides
  Timeout,       ///< no solution within the time limit
};
std::string_view toString(PlanStatus status);

struct PlanResult {
  PlanStatus status = PlanStatus::Timeout;
  JointPath path;                            ///< start to goal when solved, empty otherwise
  std::chrono::nanoseconds time{0};          ///< everything, simplification included
  std::chrono::nanoseconds simplifyTime{0};  ///< of which shortening the path
  /// Configurations the source answered (ends, planning, simplification; a batch along an edge
  /// up to its first collision).
  std::uint64_t checks = 0;
  /// Of `time`: the source answering those (the clock read around each question, see
  /// SourceUseCounter).
  std::chrono::nanoseconds checkTime{0};
  /// The planner's range when it stopped (PlannerOptions::range; 0 for BIT*, which has none).
  double range = 0;
  bool solved() const { return status == PlanStatus::Solved; }
};

/// Plans from start to goal with `source` deciding collisions, then simplifies the path for at
/// most options.simplifyTime seconds. Only an exact solution counts (OMPL's approximate solutions
/// are reported as Timeout). Throws InvalidArgument when start or
/// goal has the wrong size, a non-finite value or a value outside the joint limits.
PlanResult planMotion(const CollisionSource& source, const JointLimits& limits,
                      const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                      const PlannerOptions& options);

}  // namespace fastron
