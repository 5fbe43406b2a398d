#pragma once
// Joint-limit scaling of configurations to the model's input space [-1, 1]^d
// (paper, Sec. II-G "Joint Limits"): q_in = (2 q - q_u - q_l) / (q_u - q_l).

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <string_view>

#include "fastron/core/export.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

class JointLimits {
 public:
  JointLimits() = default;
  /// Throws InvalidArgument if the sizes differ, a value is not finite, or lower >= upper.
  JointLimits(Eigen::VectorXd lower, Eigen::VectorXd upper);
  /// [-1, 1]^d: configurations are already in input space.
  static JointLimits unitBox(std::size_t dim);

  std::size_t dim() const { return static_cast<std::size_t>(lower_.size()); }
  const Eigen::VectorXd& lower() const { return lower_; }
  const Eigen::VectorXd& upper() const { return upper_; }

  /// q_in[j] = scale[j] * q[j] + offset[j], with scale = 2 / (u - l), offset = -(u + l) / (u - l).
  const Eigen::VectorXd& scale() const { return scale_; }
  const Eigen::VectorXd& offset() const { return offset_; }

  Eigen::VectorXd toInput(std::span<const double> q) const;
  Eigen::VectorXd toJoint(std::span<const double> x) const;
  /// Row-wise versions: one configuration per row.
  Configurations toInput(const Configurations& q) const;
  Configurations toJoint(const Configurations& x) const;

  bool operator==(const JointLimits& other) const;

 private:
  Eigen::VectorXd lower_, upper_, scale_, offset_;
};

/// The bounding box of the rows of q (one configuration per row): the joint limits of data that
/// came without any. Throws InvalidArgument for no rows or a constant column, ending the message
/// with `remedy` (what the caller can give instead, e.g. "give --limits").
JointLimits rangeOf(const Eigen::Ref<const Configurations>& q, std::string_view remedy);

/// Throws InvalidArgument naming the first component of q that is not finite, or the size when
/// it differs from `dim`. `what` names the value in the message (e.g. "configuration").
void checkConfiguration(std::span<const double> q, std::size_t dim,
                        const char* what = "configuration");

}  // namespace fastron
