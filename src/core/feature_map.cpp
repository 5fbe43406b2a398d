#include "fastron/core/feature_map.h"

#include <cmath>

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
  return map;
}

FeatureMap FeatureMap::kinematic(JointLimits limits,
                                 std::shared_ptr<const PointKinematics> kinematics, double scale) {
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
  if (!std::isfinite(scale) || scale <= 0) {
    throw InvalidArgument("kinematic feature scale must be finite and > 0, got " +
                          std::to_string(scale));
  }
  FeatureMap map;
  map.kind_ = FeatureKind::Kinematic;
  map.limits_ = std::move(limits);
  map.kinematics_ = std::move(kinematics);
  map.scale_ = scale;
  return map;
}

std::size_t FeatureMap::featureDim() const {
  return kind_ == FeatureKind::Kinematic ? 3 * kinematics_->pointCount() : limits_.dim();
}

void FeatureMap::map(const double* q, double* x) const {
  if (kind_ == FeatureKind::Kinematic) {
    kinematics_->positions(q, x);
    if (scale_ != 1) {
      for (std::size_t k = 0; k < featureDim(); ++k) x[k] *= scale_;
    }
    return;
  }
  const auto& scale = limits_.scale();
  const auto& offset = limits_.offset();
  for (Eigen::Index j = 0; j < scale.size(); ++j) x[j] = scale[j] * q[j] + offset[j];
}

void FeatureMap::map(const double* q, float* x) const {
  if (kind_ == FeatureKind::Kinematic) {
    kinematics_->positions(q, x);
    if (scale_ != 1) {
      const auto s = static_cast<float>(scale_);
      for (std::size_t k = 0; k < featureDim(); ++k) x[k] *= s;
    }
    return;
  }
  const auto& scale = limits_.scale();
  const auto& offset = limits_.offset();
  for (Eigen::Index j = 0; j < scale.size(); ++j) {
    x[j] = static_cast<float>(scale[j] * q[j] + offset[j]);
  }
}

Eigen::MatrixXd FeatureMap::map(const Configurations& q) const {
  if (static_cast<std::size_t>(q.cols()) != configurationDim()) {
    throw InvalidArgument("configurations have " + std::to_string(q.cols()) +
                          " columns, expected " + std::to_string(configurationDim()));
  }
  if (!q.allFinite()) throw InvalidArgument("configurations must be finite (found NaN or inf)");
  // Row-major, so each row is one contiguous feature vector for map().
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> x(
      q.rows(), static_cast<Eigen::Index>(featureDim()));
  for (Eigen::Index i = 0; i < q.rows(); ++i) map(q.row(i).data(), x.row(i).data());
  return x;
}

std::string FeatureMap::summary() const {
  if (kind_ == FeatureKind::JointScaling) return "joints";
  return "fk (" + std::to_string(kinematics_->pointCount()) + " points)";
}

}  // namespace fastron
