#include "fastron/core/joint_limits.h"

#include <cmath>
#include <sstream>
#include <string>

#include "fastron/core/error.h"

namespace fastron {

JointLimits::JointLimits(Eigen::VectorXd lower, Eigen::VectorXd upper)
    : lower_(std::move(lower)), upper_(std::move(upper)) {
  if (lower_.size() != upper_.size()) {
    throw InvalidArgument("joint limits: " + std::to_string(lower_.size()) + " lower but " +
                          std::to_string(upper_.size()) + " upper values");
  }
  for (Eigen::Index j = 0; j < lower_.size(); ++j) {
    if (!std::isfinite(lower_[j]) || !std::isfinite(upper_[j]) || !(lower_[j] < upper_[j])) {
      throw InvalidArgument("joint limits of joint " + std::to_string(j) +
                            ": need finite lower < upper, got [" + std::to_string(lower_[j]) +
                            ", " + std::to_string(upper_[j]) + "]");
    }
  }
  scale_ = 2.0 / (upper_ - lower_).array();
  offset_ = -(upper_ + lower_).array() / (upper_ - lower_).array();
  for (Eigen::Index j = 0; j < lower_.size(); ++j) {
    // A span too narrow (subnormal) or too wide (beyond double) scales to inf or NaN features.
    const double span = upper_[j] - lower_[j];
    if (!std::isfinite(span) || !std::isfinite(scale_[j]) || !std::isfinite(offset_[j])) {
      std::ostringstream message;
      message << "joint limits of joint " << j << ": [" << lower_[j] << ", " << upper_[j]
              << "] cannot be scaled to [-1, 1] (upper - lower = " << span << ")";
      throw InvalidArgument(message.str());
    }
  }
}

JointLimits rangeOf(const Eigen::Ref<const Configurations>& q, std::string_view remedy) {
  if (q.rows() == 0)
    throw InvalidArgument("no configurations to take joint limits from; " + std::string(remedy));
  try {
    return {q.colwise().minCoeff().transpose(), q.colwise().maxCoeff().transpose()};
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(std::string(e.what()) + " in the data's range; " + std::string(remedy));
  }
}

JointLimits JointLimits::unitBox(std::size_t dim) {
  const auto n = static_cast<Eigen::Index>(dim);
  return {Eigen::VectorXd::Constant(n, -1.0), Eigen::VectorXd::Constant(n, 1.0)};
}

Eigen::VectorXd JointLimits::toInput(std::span<const double> q) const {
  checkConfiguration(q, dim());
  const Eigen::Map<const Eigen::VectorXd> v(q.data(), lower_.size());
  return scale_.cwiseProduct(v) + offset_;
}

Eigen::VectorXd JointLimits::toJoint(std::span<const double> x) const {
  checkConfiguration(x, dim(), "input-space point");
  const Eigen::Map<const Eigen::VectorXd> v(x.data(), lower_.size());
  return (v - offset_).cwiseQuotient(scale_);
}

Configurations JointLimits::toInput(const Configurations& q) const {
  if (static_cast<std::size_t>(q.cols()) != dim()) {
    throw InvalidArgument("configurations have " + std::to_string(q.cols()) +
                          " columns, joint limits have " + std::to_string(dim()));
  }
  return (q.array().rowwise() * scale_.transpose().array()).rowwise() + offset_.transpose().array();
}

Configurations JointLimits::toJoint(const Configurations& x) const {
  if (static_cast<std::size_t>(x.cols()) != dim()) {
    throw InvalidArgument("input-space points have " + std::to_string(x.cols()) +
                          " columns, joint limits have " + std::to_string(dim()));
  }
  return (x.array().rowwise() - offset_.transpose().array()).rowwise() / scale_.transpose().array();
}

bool JointLimits::operator==(const JointLimits& other) const {
  return lower_.size() == other.lower_.size() && lower_ == other.lower_ && upper_ == other.upper_;
}

void checkConfiguration(std::span<const double> q, std::size_t dim, const char* what) {
  if (q.size() != dim) {
    throw InvalidArgument(std::string(what) + " has " + std::to_string(q.size()) +
                          " values, expected " + std::to_string(dim));
  }
  for (std::size_t j = 0; j < q.size(); ++j) {
    if (!std::isfinite(q[j])) {
      throw InvalidArgument(std::string(what) + " value [" + std::to_string(j) +
                            "] is not finite (" + std::to_string(q[j]) + ")");
    }
  }
}

}  // namespace fastron
