#include "fastron/core/collision_checker.h"

#include <string>

#include "fastron/core/error.h"
#include "fastron/core/joint_limits.h"

namespace fastron {

bool CollisionChecker::inCollision(std::span<const double> q) const {
  checkConfiguration(q, dof());
  calls_.fetch_add(1, std::memory_order_relaxed);
  return check(q.data());
}

std::vector<std::uint8_t> CollisionChecker::inCollisionBatch(const Configurations& q) const {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(q.rows()));
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    out[static_cast<std::size_t>(i)] =
        inCollision({q.row(i).data(), static_cast<std::size_t>(q.cols())});
  }
  return out;
}

FunctionChecker::FunctionChecker(std::string name, std::size_t dof,
                                 std::function<bool(const double*)> fn)
    : name_(std::move(name)), dof_(dof), fn_(std::move(fn)) {
  if (dof_ == 0) throw InvalidArgument("checker '" + name_ + "': dof must be at least 1");
  if (!fn_) throw InvalidArgument("checker '" + name_ + "': no function given");
}

}  // namespace fastron
