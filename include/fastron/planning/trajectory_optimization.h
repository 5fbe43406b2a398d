#pragma once
// Trajectory optimisation on a Fastron model (issue 53): CHOMP's covariant gradient descent
// (Ratliff et al., 2009) on a path of waypoints with fixed ends, its obstacle term the model's
// collision cost (collision_cost.h) in joint space, its smoothness term the sum of squared steps.
// What it returns is the model's word; optimizeVerified checks it exactly and lets the model learn
// what verification finds, as planVerifiedLearning does for sampled plans.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "fastron/core/collision_checker.h"
#include "fastron/core/export.h"
#include "fastron/core/joint_limits.h"
#include "fastron/core/model.h"
#include "fastron/planning/motion.h"
#include "fastron/planning/planner.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace FASTRON_API fastron {

/// Settings of optimizeTrajectory. Defaults measured on Baxter's three boxes and the generated
/// families (docs/planning.md, "Trajectory optimisation").
struct TrajectoryOptions {
  /// Joint units between the waypoints of a straight line made by straightPath (at least 8
  /// waypoints in all).
  double spacing = 0.05;
  /// The cost's hinge (collision_cost.h), in score units: waypoints scoring above -margin are
  /// pushed out, so a path leaves the model's boundary with some room.
  double margin = 1.0;
  /// The largest change of one joint of one waypoint that the collision term makes per iteration
  /// (joint units): the covariant step is scaled to it, whatever the score's scale.
  double maxStep = 0.03;
  /// The share of the way back to the straight line between the ends that each iteration takes
  /// (CHOMP's smoothness step, through the same metric): 0 keeps every bend the collision term
  /// made.
  double smoothing = 0.005;
  std::size_t maxIterations = 400;
  /// Iterations without a 1% fall of the cost after which the interior waypoints get a random
  /// smooth kick (a path through the middle of a collision feels pushes that cancel), whose
  /// largest joint change is `kick` (joint units).
  std::size_t stallIterations = 30;
  double kick = 0.2;
  std::uint64_t seed = 1;  ///< of the kicks
  /// Seconds an optimisation may take (optimizeVerified: all its rounds and checks together);
  /// 0: no limit but maxIterations.
  double timeLimit = 0;
  /// Step at which the path's edges are checked on the model before it is called free.
  double modelResolution = 0.06;
};

/// Throws InvalidArgument naming the field of an option out of range.
void validate(const TrajectoryOptions& options);

/// Waypoints from `start` to `goal` on a straight line, `spacing` apart at most (at least 8).
/// Throws InvalidArgument on ends of different sizes or a spacing that is not positive.
JointPath straightPath(const Eigen::VectorXd& start, const Eigen::VectorXd& goal, double spacing);

/// `path` with every edge cut into pieces of at most `spacing` (and at least 8 waypoints in all):
/// the waypoints an optimisation moves. Throws InvalidArgument on an empty path or a spacing that
/// is not positive.
JointPath densePath(const JointPath& path, double spacing);

/// The optimiser's settings for gradient repair (VerifyRepairOptions::gradientRepair): the
/// defaults, the model's edge step of `planner` (modelStep), fewer iterations and the time a
/// stretch's bridge gets (stretchShare of the time limit): a stretch that does not come free soon
/// is replanned.
TrajectoryOptions gradientRepairOptions(const PlannerOptions& planner);

struct OptimizedTrajectory {
  JointPath path;  ///< the same ends as the initial path, the same number of waypoints
  /// Every state of the path at modelResolution is free on the model, but for the runs joined to
  /// an end that the model finds colliding, each at most a quarter of the states (the ends do not
  /// move: an end the exact checker found free may lie under the model's smooth boundary, and the
  /// exact check judges its neighbours).
  bool freeOnModel = false;
  std::size_t iterations = 0;
  /// The path's collision cost (through its states at modelResolution) before each iteration, and
  /// at the end.
  std::vector<double> costs;
  std::chrono::nanoseconds time{0};
};

/// Moves the interior waypoints of `initial` (at least three waypoints) out of the model's
/// collisions: each iteration takes the gradient of the path's collision cost through every state
/// at modelResolution (the states a check looks at, their gradients shared by the waypoints of
/// their edge), preconditions it with
/// the inverse of the smoothness metric (a local push spreads smoothly along the path), scales it
/// to maxStep, adds the smoothing step, and clamps to the joint limits; a stalled cost gets a
/// random smooth kick (stallIterations, kick). Stops when the path is free on the model, when
/// only the neighbours of an end still collide on it and the cost has stalled, or after
/// maxIterations or timeLimit. The same inputs give the same path (unless the time limit cuts it
/// short). Throws InvalidArgument on bad options,
/// waypoints of the wrong size or outside the limits.
OptimizedTrajectory optimizeTrajectory(const Model& model, const JointLimits& limits,
                                       const JointPath& initial, const TrajectoryOptions& options);

/// The result of optimizeVerified.
struct VerifiedTrajectory {
  PlanStatus status = PlanStatus::Timeout;  ///< Solved only when `exact` verified the path free
  JointPath path;                           ///< the last path optimised
  std::size_t rounds = 0;      ///< optimisations (1 + the times the model learned and went on)
  std::size_t iterations = 0;  ///< over every round
  std::chrono::nanoseconds optimizeTime{0}, verifyTime{0}, learnTime{0};
  std::vector<double> costs;  ///< the first round's OptimizedTrajectory::costs
  std::string failure;
  std::chrono::nanoseconds totalTime() const { return optimizeTime + verifyTime + learnTime; }
};

/// From the straight line between `start` and `goal`: optimizes on the proxy's model, checks the
/// path with `exact` at `resolution`, and while it collides (up to `rounds` times) lets the model
/// learn the answers it got wrong (as planVerifiedLearning) and optimizes again: from the last
/// path when it was free on the model, from the straight line with other kicks when it stayed in
/// the model's collisions. Never returns Solved on the model's word. Start and goal must be free
/// under `exact` (else InvalidStart / InvalidGoal). Throws InvalidArgument on a null checker, a
/// resolution that is not positive or bad options. Not while the proxy updates in the
/// background.
VerifiedTrajectory optimizeVerified(ProxyCollisionDetector& proxy,
                                    const std::shared_ptr<const CollisionChecker>& exact,
                                    const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                                    double resolution, const TrajectoryOptions& options,
                                    std::size_t rounds = 4);

}  // namespace fastron
