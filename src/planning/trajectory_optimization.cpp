#include "fastron/planning/trajectory_optimization.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "fastron/core/error.h"
#include "fastron/core/recording_checker.h"
#include "fastron/planning/collision_cost.h"
#include "fastron/planning/parallel_check.h"

namespace fastron {

namespace {

using Clock = std::chrono::steady_clock;

void checkPositive(double value, const char* field) {
  if (!std::isfinite(value) || value <= 0) {
    throw InvalidArgument(std::string("TrajectoryOptions::") + field +
                          " must be finite and > 0, got " + std::to_string(value));
  }
}

/// The inverse of CHOMP's smoothness metric A = K^T K for N interior waypoints, K the finite
/// differences of consecutive waypoints (A tridiagonal: 2 on the diagonal, -1 beside it), in
/// closed form: (A^-1)_ij = min(i, j) (N + 1 - max(i, j)) / (N + 1), 1-based.
Eigen::MatrixXd inverseSmoothnessMetric(Eigen::Index n) {
  Eigen::MatrixXd inverse(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      inverse(i, j) = static_cast<double>(std::min(i, j) + 1) *
                      static_cast<double>(n - std::max(i, j)) / static_cast<double>(n + 1);
    }
  }
  return inverse;
}

Configurations rowsOf(const JointPath& path) {
  Configurations rows(static_cast<Eigen::Index>(path.size()), path.front().size());
  for (std::size_t t = 0; t < path.size(); ++t)
    rows.row(static_cast<Eigen::Index>(t)) = path[t].transpose();
  return rows;
}

JointPath pathOf(const Configurations& rows) {
  JointPath path;
  path.reserve(static_cast<std::size_t>(rows.rows()));
  for (Eigen::Index t = 0; t < rows.rows(); ++t) path.emplace_back(rows.row(t).transpose());
  return path;
}

/// Whether the states along a path at some resolution are free on the model.
enum class ModelFreedom {
  Free,
  /// Free but for the runs joined to an end that the model finds colliding, each at most a
  /// quarter of the states: the ends do not move, and an end that the exact checker found free may
  /// lie under the model's smooth boundary, its neighbours with it.
  FreeButNearTheEnds,
  Colliding,
};

/// The collision cost of the path through every state at the resolution (a finer trapezoid
/// integral than over the waypoints alone: a bend between two free waypoints can cross an
/// obstacle), its gradient with respect to the waypoints, and the states' scores.
PathCollisionCost costThroughEdges(const Model& model, const Configurations& rows,
                                   double resolution, double margin) {
  const JointPath path = pathOf(rows);
  PathCollisionCost states = pathCollisionCost(model, statesAlongPath(path, resolution), margin);
  PathCollisionCost out{states.cost, std::move(states.scores),
                        Configurations::Zero(rows.rows(), rows.cols())};
  // State i of edge e is (1 - i / n) q_e + (i / n) q_e+1 (statesAlongPath's order); the last
  // state is the last waypoint.
  Eigen::Index row = 0;
  const std::vector<std::size_t> segments = edgeSegments(path, resolution);
  for (std::size_t e = 0; e < segments.size(); ++e) {
    const auto edge = static_cast<Eigen::Index>(e);
    for (std::size_t i = 0; i < segments[e]; ++i, ++row) {
      const double share = static_cast<double>(i) / static_cast<double>(segments[e]);
      out.gradient.row(edge) += (1 - share) * states.gradient.row(row);
      out.gradient.row(edge + 1) += share * states.gradient.row(row);
    }
  }
  out.gradient.row(rows.rows() - 1) += states.gradient.row(row);
  return out;
}

/// `f`: the scores of the states along a path, in order.
ModelFreedom freedomOnModel(const Eigen::VectorXd& f) {
  const Eigen::Index n = f.size(), most = n / 4;
  Eigen::Index first = 0, last = n - 1;
  while (first < most && f[first] > 0) ++first;
  while (last >= n - most && f[last] > 0) --last;
  if (!(f.segment(first, last - first + 1).array() <= 0).all()) return ModelFreedom::Colliding;
  return first == 0 && last == n - 1 ? ModelFreedom::Free : ModelFreedom::FreeButNearTheEnds;
}

/// The interior rows of `gradient` without their components along the path (CHOMP projects its
/// obstacle gradient the same way): a push along the path only slides waypoints, and where the
/// learned collisions sit on the path itself (verification labels its own states) it is most of
/// the gradient, so that, scaled to a step, it would leave no room to move across.
Configurations acrossThePath(const Configurations& rows, const Configurations& gradient) {
  const Eigen::Index interior = rows.rows() - 2;
  Configurations across = gradient.middleRows(1, interior);
  for (Eigen::Index t = 0; t < interior; ++t) {
    const Eigen::RowVectorXd tangent = rows.row(t + 2) - rows.row(t);
    const double length = tangent.norm();
    if (length > 0) across.row(t) -= (across.row(t).dot(tangent) / (length * length)) * tangent;
  }
  return across;
}

void checkInitial(const JointPath& initial, const JointLimits& limits) {
  if (initial.size() < 3) {
    throw InvalidArgument("trajectory optimisation needs at least three waypoints, got " +
                          std::to_string(initial.size()));
  }
  checkWaypointSizes(initial, limits.dim());
  for (std::size_t t = 0; t < initial.size(); ++t) {
    const std::string what = "waypoint " + std::to_string(t);
    checkConfiguration({initial[t].data(), limits.dim()}, limits.dim(), what.c_str());
    if ((initial[t].array() < limits.lower().array()).any() ||
        (initial[t].array() > limits.upper().array()).any()) {
      throw InvalidArgument(what + " is outside the joint limits");
    }
  }
}

}  // namespace

void validate(const TrajectoryOptions& o) {
  checkPositive(o.spacing, "spacing");
  checkPositive(o.maxStep, "maxStep");
  checkPositive(o.modelResolution, "modelResolution");
  checkPositive(o.kick, "kick");
  if (!std::isfinite(o.timeLimit) || o.timeLimit < 0) {
    throw InvalidArgument("TrajectoryOptions::timeLimit must be finite and >= 0, got " +
                          std::to_string(o.timeLimit));
  }
  if (o.stallIterations == 0)
    throw InvalidArgument("TrajectoryOptions::stallIterations must be > 0, got 0");
  if (!std::isfinite(o.margin) || o.margin < 0) {
    throw InvalidArgument("TrajectoryOptions::margin must be finite and >= 0, got " +
                          std::to_string(o.margin));
  }
  if (!(o.smoothing >= 0 && o.smoothing <= 1)) {
    throw InvalidArgument("TrajectoryOptions::smoothing must be in [0, 1], got " +
                          std::to_string(o.smoothing));
  }
}

JointPath densePath(const JointPath& path, double spacing) {
  if (path.empty()) throw InvalidArgument("densePath: the path has no waypoint");
  checkWaypointSizes(path, static_cast<std::size_t>(path.front().size()));
  checkPositive(spacing, "spacing");
  const double length = pathLength(path);
  JointPath dense{path.front()};
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const double edge = (path[k + 1] - path[k]).norm();
    // At least 7 pieces over the whole path, shared by length.
    const double pieces =
        std::max(std::ceil(edge / spacing), length > 0 ? std::ceil(7 * edge / length) : 0.0);
    const auto n = std::max<std::size_t>(1, static_cast<std::size_t>(pieces));
    for (std::size_t t = 1; t <= n; ++t) {
      const double s = static_cast<double>(t) / static_cast<double>(n);
      dense.emplace_back(t == n ? path[k + 1]
                                : Eigen::VectorXd((1 - s) * path[k] + s * path[k + 1]));
    }
  }
  return dense;
}

JointPath straightPath(const Eigen::VectorXd& start, const Eigen::VectorXd& goal, double spacing) {
  if (start.size() != goal.size()) {
    throw InvalidArgument("straightPath: start has " + std::to_string(start.size()) +
                          " values, goal " + std::to_string(goal.size()));
  }
  return densePath({start, goal}, spacing);
}

TrajectoryOptions gradientRepairOptions(const PlannerOptions& planner) {
  TrajectoryOptions options;
  options.modelResolution = modelStep(planner);
  options.maxIterations = 200;
  options.timeLimit = planner.timeLimit * planner.verify.stretchShare;
  return options;
}

OptimizedTrajectory optimizeTrajectory(const Model& model, const JointLimits& limits,
                                       const JointPath& initial, const TrajectoryOptions& o) {
  validate(o);
  checkInitial(initial, limits);
  const auto began = Clock::now();
  Configurations rows = rowsOf(initial);
  const Eigen::Index last = rows.rows() - 1, interior = rows.rows() - 2;
  const Eigen::MatrixXd inverseMetric = inverseSmoothnessMetric(interior);
  // The minimum of the smoothness term with these ends: the straight line, evenly spaced.
  Configurations straight(interior, rows.cols());
  for (Eigen::Index t = 1; t < last; ++t) {
    const double s = static_cast<double>(t) / static_cast<double>(last);
    straight.row(t - 1) = (1 - s) * rows.row(0) + s * rows.row(last);
  }
  const Eigen::RowVectorXd lower = limits.lower().transpose(), upper = limits.upper().transpose();
  auto moving = rows.middleRows(1, interior);
  const auto clamp = [&] {
    for (Eigen::Index t = 0; t < interior; ++t)
      moving.row(t) = moving.row(t).cwiseMax(lower).cwiseMin(upper);
  };
  // A displacement of the interior waypoints through the metric, its largest joint change `size`.
  const auto smoothStep = [&](const Configurations& direction, double size) {
    Configurations step = inverseMetric * direction;
    const double largest = step.cwiseAbs().maxCoeff();
    if (largest > 0) step *= size / largest;
    return step;
  };
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> normal;
  double best = std::numeric_limits<double>::infinity(), size = o.maxStep;
  std::size_t stalled = 0, kicks = 0;
  PathCollisionCost cost = costThroughEdges(model, rows, o.modelResolution, o.margin);
  OptimizedTrajectory out;
  for (;; ++out.iterations) {
    out.costs.push_back(cost.cost);
    const ModelFreedom freedom = freedomOnModel(cost.scores);
    out.freeOnModel = freedom != ModelFreedom::Colliding;
    if (freedom == ModelFreedom::Free || out.iterations == o.maxIterations) break;
    if (o.timeLimit > 0 && Clock::now() - began > std::chrono::duration<double>(o.timeLimit)) break;
    // A path through the middle of a collision feels pushes that cancel (CHOMP's local minima):
    // when the cost has not fallen by 1% for stallIterations, a random smooth kick; unless only
    // the ends' neighbours still collide on the model, which no push frees.
    if (cost.cost < 0.99 * best) {
      best = cost.cost;
      stalled = 0;
    } else if (++stalled == o.stallIterations && out.freeOnModel) {
      break;
    } else if (stalled == o.stallIterations) {
      moving += smoothStep(
          Configurations::NullaryExpr(interior, rows.cols(), [&] { return normal(rng); }),
          o.kick * static_cast<double>(++kicks));
      clamp();
      cost = costThroughEdges(model, rows, o.modelResolution, o.margin);
      best = std::numeric_limits<double>::infinity();
      stalled = 0;
      size = o.maxStep;
      continue;
    }
    // A step that raises the cost overshot a narrow peak: taken back and halved; one that
    // lowers it grows again, up to maxStep.
    const Configurations before = rows;
    moving -=
        smoothStep(acrossThePath(rows, cost.gradient), size) + o.smoothing * (moving - straight);
    clamp();
    PathCollisionCost next = costThroughEdges(model, rows, o.modelResolution, o.margin);
    if (next.cost > cost.cost && size > 1e-3 * o.maxStep) {
      rows = before;
      size /= 2;
      continue;
    }
    size = std::min(o.maxStep, 1.5 * size);
    cost = std::move(next);
  }
  out.path = pathOf(rows);
  out.time = Clock::now() - began;
  return out;
}

VerifiedTrajectory optimizeVerified(ProxyCollisionDetector& proxy,
                                    const std::shared_ptr<const CollisionChecker>& exact,
                                    const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                                    double resolution, const TrajectoryOptions& options,
                                    std::size_t rounds) {
  if (!exact) throw InvalidArgument("optimizeVerified: the exact checker is null");
  if (!std::isfinite(resolution) || resolution <= 0) {
    throw InvalidArgument("optimizeVerified: the resolution must be finite and > 0, got " +
                          std::to_string(resolution));
  }
  validate(options);
  VerifiedTrajectory result;
  if (exact->inCollision({start.data(), static_cast<std::size_t>(start.size())})) {
    result.status = PlanStatus::InvalidStart;
    result.failure = "the start collides under " + exact->name();
    return result;
  }
  if (exact->inCollision({goal.data(), static_cast<std::size_t>(goal.size())})) {
    result.status = PlanStatus::InvalidGoal;
    result.failure = "the goal collides under " + exact->name();
    return result;
  }
  auto recorder = std::make_shared<RecordingChecker>(exact);
  const JointPath straight = straightPath(start, goal, options.spacing);
  JointPath path = straight;
  TrajectoryOptions roundOptions = options;
  const auto began = Clock::now();
  for (;;) {
    const std::shared_ptr<const Model> model = proxy.model();
    OptimizedTrajectory optimized = optimizeTrajectory(*model, proxy.limits(), path, roundOptions);
    ++result.rounds;
    result.iterations += optimized.iterations;
    result.optimizeTime += optimized.time;
    if (result.rounds == 1) result.costs = std::move(optimized.costs);
    // A path stuck in the model's collisions starts the next round again from the straight
    // line, with other kicks; one free on the model goes on from where it is.
    const bool stuck = !optimized.freeOnModel;
    path = std::move(optimized.path);
    roundOptions.seed = options.seed + result.rounds;
    auto checkBegan = Clock::now();
    const PathCheck check = checkPathParallel(*recorder, path, resolution);
    result.verifyTime += Clock::now() - checkBegan;
    if (check.valid()) {
      result.status = PlanStatus::Solved;
      break;
    }
    if (result.rounds > rounds) {
      result.failure = "the path still collided under " + exact->name() + " after " +
                       std::to_string(result.rounds) + " optimisations";
      break;
    }
    const double left =
        options.timeLimit - std::chrono::duration<double>(Clock::now() - began).count();
    if (options.timeLimit > 0 && left <= 0) {
      result.failure = "the path still collided under " + exact->name() +
                       " when the time limit of " + std::to_string(options.timeLimit) + " s was up";
      break;
    }
    roundOptions.timeLimit = options.timeLimit > 0 ? left : 0;
    const auto learnBegan = Clock::now();
    const Dataset missed = answersMissedBy(*model, recorder->take());
    if (missed.size() == 0) {
      result.failure = "the model already agrees with every exact answer along the path";
      break;
    }
    proxy.addObservations(missed);
    proxy.learnObservations();
    result.learnTime += Clock::now() - learnBegan;
    if (stuck) path = straight;
  }
  result.path = std::move(path);
  return result;
}

}  // namespace fastron
