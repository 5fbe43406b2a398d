#include "fastron/planning/collision_cost.h"

#include <cmath>
#include <string>

#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "fastron/core/error.h"

namespace fastron {

namespace ob = ompl::base;

namespace {

void checkMargin(double margin) {
  if (!std::isfinite(margin) || margin < 0) {
    throw InvalidArgument("collision cost margin must be finite and >= 0, got " +
                          std::to_string(margin));
  }
}

}  // namespace

StateCollisionCost stateCollisionCost(const Model& model, const Eigen::VectorXd& q, double margin) {
  checkMargin(margin);
  const Model::ScoreGradient f =
      model.scoreGradient({q.data(), static_cast<std::size_t>(q.size())});
  const double hinge = std::max(0.0, f.score + margin);
  return {0.5 * hinge * hinge, f.score, hinge * f.gradient};
}

PathCollisionCost pathCollisionCost(const Model& model, const Configurations& waypoints,
                                    double margin) {
  checkMargin(margin);
  if (waypoints.rows() < 2) {
    throw InvalidArgument("a path's collision cost needs at least two waypoints, got " +
                          std::to_string(waypoints.rows()));
  }
  const Model::ScoreGradients f = model.scoreGradients(waypoints);  // checks the columns
  const Eigen::Index n = waypoints.rows();
  const Eigen::ArrayXd hinge = (f.scores.array() + margin).max(0.0);
  const Eigen::ArrayXd c = 0.5 * hinge.square();
  PathCollisionCost out{0, f.scores, Configurations::Zero(n, waypoints.cols())};
  for (Eigen::Index t = 0; t + 1 < n; ++t) {
    const Eigen::RowVectorXd edge = waypoints.row(t + 1) - waypoints.row(t);
    const double length = edge.norm();
    const double mean = 0.5 * (c[t] + c[t + 1]);
    out.cost += mean * length;
    // d/dq_t of 1/2 (c_t + c_t+1) L: 1/2 L dc_t/dq_t - mean u, u the edge's direction.
    out.gradient.row(t) += 0.5 * length * hinge[t] * f.gradients.row(t);
    out.gradient.row(t + 1) += 0.5 * length * hinge[t + 1] * f.gradients.row(t + 1);
    if (length > 0) {
      out.gradient.row(t) -= (mean / length) * edge;
      out.gradient.row(t + 1) += (mean / length) * edge;
    }
  }
  return out;
}

ModelCollisionObjective::ModelCollisionObjective(const ob::SpaceInformationPtr& si,
                                                 std::shared_ptr<const Model> model, double margin,
                                                 bool interpolate)
    : ob::StateCostIntegralObjective(si, interpolate), model_(std::move(model)), margin_(margin) {
  if (!model_) throw InvalidArgument("ModelCollisionObjective: the model is null");
  checkMargin(margin);
  if (si->getStateDimension() != model_->dim()) {
    throw InvalidArgument("ModelCollisionObjective: the model has " +
                          std::to_string(model_->dim()) + " joints, the state space " +
                          std::to_string(si->getStateDimension()));
  }
  description_ = "Fastron model collision cost";
}

ob::Cost ModelCollisionObjective::stateCost(const ob::State* state) const {
  const double* q = state->as<ob::RealVectorStateSpace::StateType>()->values;
  const double hinge = std::max(0.0, model_->score(q) + margin_);
  return ob::Cost(0.5 * hinge * hinge);
}

ob::OptimizationObjectivePtr lengthAndCollisionObjective(const ob::SpaceInformationPtr& si,
                                                         std::shared_ptr<const Model> model,
                                                         double weight, double margin) {
  if (!std::isfinite(weight) || weight < 0) {
    throw InvalidArgument("collision cost weight must be finite and >= 0, got " +
                          std::to_string(weight));
  }
  auto sum = std::make_shared<ob::MultiOptimizationObjective>(si);
  sum->addObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si), 1.0);
  sum->addObjective(std::make_shared<ModelCollisionObjective>(si, std::move(model), margin),
                    weight);
  sum->lock();
  return sum;
}

}  // namespace fastron
