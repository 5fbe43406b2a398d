#include "fastron/core/collision_checker.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "fastron/core/error.h"
#include "fastron/core/joint_limits.h"
#include "fastron/core/motion_states.h"

namespace fastron {

bool CollisionChecker::inCollision(std::span<const double> q) const {
  checkConfiguration(q, dof());
  calls_.fetch_add(1, std::memory_order_relaxed);
  return check(q.data());
}

std::vector<std::uint8_t> CollisionChecker::inCollisionBatch(const Configurations& q) const {
  checkColumns(q);
  std::vector<std::uint8_t> out(static_cast<std::size_t>(q.rows()));
  inCollisionEach(q.data(), out.size(), out.data());
  return out;
}

void CollisionChecker::inCollisionEach(const double* q, std::size_t n, std::uint8_t* out) const {
  checkFinite(q, n);
  calls_.fetch_add(
      n, std::memory_order_relaxed);  // before: a call that throws counts, as in inCollision
  checkEach(q, n, out);
}

void CollisionChecker::checkEach(const double* q, std::size_t n, std::uint8_t* out) const {
  const std::size_t dim = dof();
  for (std::size_t i = 0; i < n; ++i) out[i] = check(q + i * dim) ? 1 : 0;
}

void CollisionChecker::checkColumns(const Configurations& q) const {
  if (static_cast<std::size_t>(q.cols()) != dof()) {
    throw InvalidArgument("configurations have " + std::to_string(q.cols()) + " columns, " +
                          name() + " checks " + std::to_string(dof()) + " joints");
  }
}

void CollisionChecker::checkFinite(const double* q, std::size_t n) const {
  const std::size_t dim = dof();
  for (std::size_t i = 0; i < n; ++i) {
    const std::span<const double> row(q + i * dim, dim);
    if (!std::ranges::all_of(row, [](double v) { return std::isfinite(v); })) {
      checkConfiguration(row, dim, ("configuration " + std::to_string(i)).c_str());
    }
  }
}

std::size_t CollisionChecker::firstInCollision(const Configurations& q) const {
  checkColumns(q);
  return firstInCollision(q.data(), static_cast<std::size_t>(q.rows()));
}

std::size_t CollisionChecker::firstInCollision(const double* q, std::size_t n) const {
  checkFinite(q, n);
  const std::size_t first = checkFirst(q, n);
  calls_.fetch_add(std::min(first + 1, n), std::memory_order_relaxed);
  return first;
}

std::size_t CollisionChecker::checkFirst(const double* q, std::size_t n) const {
  const std::size_t dim = dof();
  for (std::size_t i = 0; i < n; ++i) {
    if (check(q + i * dim)) return i;
  }
  return n;
}

CollisionChecker::MotionCheck CollisionChecker::motionCollision(const double* from,
                                                                const double* to,
                                                                std::size_t segments) const {
  checkFinite(from, 1);
  checkFinite(to, 1);
  if (segments == 0) return {};
  const MotionCheck answer = checkMotion(from, to, segments);
  calls_.fetch_add(answer.looked, std::memory_order_relaxed);
  return answer;
}

CollisionChecker::MotionCheck CollisionChecker::checkMotion(const double* from, const double* to,
                                                            std::size_t segments) const {
  return checkMotionStateByState(from, to, segments);
}

CollisionChecker::MotionCheck CollisionChecker::checkMotionStateByState(
    const double* from, const double* to, std::size_t segments) const {
  std::vector<double> states;
  motionStates(from, to, dof(), segments, states);
  const std::size_t first = checkFirst(states.data(), segments);
  if (first == segments) return {0, segments};
  return {bisectionIndex(segments, first), first + 1};
}

FunctionChecker::FunctionChecker(std::string name, std::size_t dof,
                                 std::function<bool(const double*)> fn)
    : name_(std::move(name)), dof_(dof), fn_(std::move(fn)) {
  if (dof_ == 0) throw InvalidArgument("checker '" + name_ + "': dof must be at least 1");
  if (!fn_) throw InvalidArgument("checker '" + name_ + "': no function given");
}

}  // namespace fastron
