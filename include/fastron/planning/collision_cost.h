#pragma once
// A smooth cost of being in collision, from a Fastron model's score (issue 53): for trajectory
// optimisation (trajectory_optimization.h), gradient repair (verify_repair.h) and OMPL's
// optimising planners (ModelCollisionObjective).
//
// Per state, a squared hinge on the score plus a margin: c(q) = 1/2 max(0, f(q) + m)^2, whose
// gradient is max(0, f(q) + m) df/dq (continuous, zero where the model finds q free by more than
// m). Along a path, the trapezoid integral of c over its polyline (what OMPL's
// StateCostIntegralObjective sums without interpolation): C = sum over edges of
// 1/2 (c(q_t) + c(q_t+1)) |q_t+1 - q_t|, so a long stretch in collision costs more than a short
// one.

#include <Eigen/Core>
#include <memory>

#include <ompl/base/objectives/StateCostIntegralObjective.h>

#include "fastron/core/export.h"
#include "fastron/core/model.h"
#include "fastron/planning/motion.h"

namespace FASTRON_API fastron {

/// c(q) = 1/2 max(0, f(q) + margin)^2 and its gradient.
struct StateCollisionCost {
  double cost = 0;
  double score = 0;          ///< f(q)
  Eigen::VectorXd gradient;  ///< dc/dq, dim() values
};
/// Throws InvalidArgument on a wrong size, a non-finite value or a negative or non-finite margin.
StateCollisionCost stateCollisionCost(const Model& model, const Eigen::VectorXd& q, double margin);

/// C of a path (waypoints as rows, at least two) and its gradient with respect to every waypoint,
/// ends included (a caller that keeps them fixed ignores their rows).
struct PathCollisionCost {
  double cost = 0;
  Eigen::VectorXd scores;   ///< f at each waypoint
  Configurations gradient;  ///< dC/dq_t, one row per waypoint
};
/// Throws InvalidArgument on fewer than two rows, a wrong number of columns, a non-finite value
/// or a bad margin.
PathCollisionCost pathCollisionCost(const Model& model, const Configurations& waypoints,
                                    double margin);

/// An OMPL objective whose cost is the integral of c along a motion (OMPL's
/// StateCostIntegralObjective with c as the state cost; with interpolation, motions are cut at
/// the space's longest valid segment, as the planner's checks are). The model is a snapshot:
/// thread-safe as the model is. Combine it with path length through
/// lengthAndCollisionObjective.
class ModelCollisionObjective final : public ompl::base::StateCostIntegralObjective {
 public:
  /// Throws InvalidArgument on a null model, a model of another dimension than the space, or a
  /// bad margin.
  ModelCollisionObjective(const ompl::base::SpaceInformationPtr& si,
                          std::shared_ptr<const Model> model, double margin,
                          bool interpolate = true);
  ompl::base::Cost stateCost(const ompl::base::State* state) const override;

 private:
  std::shared_ptr<const Model> model_;
  double margin_;
};

/// Path length plus `weight` times the model's collision cost (OMPL's MultiOptimizationObjective),
/// for RRT*, BIT* and the other optimising planners: they then trade length for clearance. Throws
/// InvalidArgument on a negative or non-finite weight, and as ModelCollisionObjective.
ompl::base::OptimizationObjectivePtr lengthAndCollisionObjective(
    const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const Model> model, double weight,
    double margin);

}  // namespace fastron
