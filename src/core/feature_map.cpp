#include "fastron/core/feature_map.h"

#include <algorithm>
#include <array>
#include <vector>

#include "fastron/core/error.h"

namespace fastron {

std::string_view toString(FeatureKind kind) {
  return kind == FeatureKind::Kinematic ? "fk" : "joints";
}

FeatureKind parseFeatureKind(std::string_view name) {
  if (name == "joints") return FeatureKind::JointScaling;
  if (name == "fk") return FeatureKind::Kinematic;
  throw InvalidArgument("unknown feature kind '" + std::string(name) + "' (use joints or fk)");
}

FeatureMap FeatureMap::jointScaling(JointLimits limits) {
  FeatureMap map;
  map.limits_ = std::move(limits);
  map.featureDim_ = map.limits_.dim();
  return map;
}

FeatureMap FeatureMap::kinematic(JointLimits limits,
                                 std::shared_ptr<const PointKinematics> kinematics) {
  if (!kinematics) throw InvalidArgument("kinematic features need kinematics, got none");
  if (kinematics->dof() != limits.dim()) {
    throw InvalidArgument("kinematic features: the kinematics have " +
                          std::to_string(kinematics->dof()) + " joints but the joint limits " +
                          std::to_string(limits.dim()));
  }
  const std::size_t points = kinematics->pointCount();
  if (points == 0 || 3 * points > kMaxFeatureDimension) {
    throw InvalidArgument("kinematic features need 1 to " +
                          std::to_string(kMaxFeatureDimension / 3) + " control points, got " +
                          std::to_string(points));
  }
  FeatureMap map;
  map.kind_ = FeatureKind::Kinematic;
  map.limits_ = std::move(limits);
  map.kinematics_ = std::move(kinematics);
  map.featureDim_ = 3 * points;
  return map;
}

template <class T>
void FeatureMap::mapTo(const double* q, T* x) const {
  if (kind_ == FeatureKind::Kinematic) {
    kinematics_->positions(q, x);
    return;
  }
  const auto& scale = limits_.scale();
  const auto& offset = limits_.offset();
  for (Eigen::Index j = 0; j < scale.size(); ++j) {
    x[j] = static_cast<T>(scale[j] * q[j] + offset[j]);
  }
}

void FeatureMap::map(const double* q, double* x) const {
  mapTo(q, x);
}
void FeatureMap::map(const double* q, float* x) const {
  mapTo(q, x);
}

void FeatureMap::mapBatch(const double* q, std::size_t n, float* x) const {
  if (kind_ == FeatureKind::Kinematic) {
    kinematics_->positionsBatch(q, n, x);
    return;
  }
  const std::size_t dof = configurationDim();
  for (std::size_t i = 0; i < n; ++i) mapTo(q + i * dof, x + i * featureDim_);
}

void FeatureMap::jacobian(const double* q, double* x, double* jacobian) const {
  if (kind_ == FeatureKind::Kinematic) {
    kinematics_->jacobian(q, x, jacobian);
    return;
  }
  const std::size_t dof = configurationDim();
  std::fill_n(jacobian, dof * dof, 0.0);
  mapTo(q, x);
  for (std::size_t j = 0; j < dof; ++j)
    jacobian[j * dof + j] = limits_.scale()[static_cast<Eigen::Index>(j)];
}

void PointKinematics::jacobian(const double* q, double* out, double* jacobian) const {
  constexpr double kStep = 1e-6;
  const std::size_t dofs = dof(), coordinates = 3 * pointCount();
  positions(q, out);
  std::vector<double> moved(q, q + dofs), plus(coordinates), minus(coordinates);
  for (std::size_t j = 0; j < dofs; ++j) {
    moved[j] = q[j] + kStep;
    positions(moved.data(), plus.data());
    moved[j] = q[j] - kStep;
    positions(moved.data(), minus.data());
    moved[j] = q[j];
    for (std::size_t c = 0; c < coordinates; ++c)
      jacobian[c * dofs + j] = (plus[c] - minus[c]) / (2 * kStep);
  }
}

void PointKinematics::positionsBatch(const double* q, std::size_t n, float* out) const {
  const std::size_t dofs = dof(), coordinates = 3 * pointCount();
  for (std::size_t i = 0; i < n; ++i) positions(q + i * dofs, out + i * coordinates);
}

void FeatureMap::check(const Configurations& q) const {
  if (static_cast<std::size_t>(q.cols()) != configurationDim()) {
    throw InvalidArgument("configurations have " + std::to_string(q.cols()) +
                          " columns, expected " + std::to_string(configurationDim()));
  }
  if (!q.allFinite()) throw InvalidArgument("configurations must be finite (found NaN or inf)");
}

Eigen::MatrixXd FeatureMap::map(const Configurations& q) const {
  check(q);
  Eigen::MatrixXd x(q.rows(), static_cast<Eigen::Index>(featureDim()));
  mapRows(q, 0, q.rows(), x);
  return x;
}

void FeatureMap::mapRows(const Configurations& q, Eigen::Index begin, Eigen::Index end,
                         Eigen::MatrixXd& x) const {
  const auto d = static_cast<Eigen::Index>(featureDim());
  std::array<double, kMaxFeatureDimension> row{};
  for (Eigen::Index i = begin; i < end; ++i) {
    map(q.row(i).data(), row.data());
    x.row(i) = Eigen::Map<const Eigen::RowVectorXd>(row.data(), d);
  }
}

std::string FeatureMap::summary() const {
  if (kind_ == FeatureKind::JointScaling) return "joints";
  return "fk (" + std::to_string(kinematics_->pointCount()) + " points)";
}

}  // namespace fastron
