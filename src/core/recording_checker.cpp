#include "fastron/core/recording_checker.h"

#include <algorithm>
#include <span>

#include "fastron/core/error.h"
#include "fastron/core/motion_states.h"

namespace fastron {

RecordingChecker::RecordingChecker(std::shared_ptr<const CollisionChecker> inner)
    : inner_(std::move(inner)) {
  if (!inner_) throw InvalidArgument("RecordingChecker: the checker is a null pointer");
}

bool RecordingChecker::check(const double* q) const {
  return checkFirst(q, 1) == 0;
}

void RecordingChecker::record(const double* q, std::size_t n, const auto& inCollision) const {
  const std::lock_guard lock(mutex_);
  values_.insert(values_.end(), q, q + n * dof());
  for (std::size_t i = 0; i < n; ++i) {
    labels_.push_back(inCollision(i) ? std::int8_t{1} : std::int8_t{-1});
  }
}

std::size_t RecordingChecker::checkFirst(const double* q, std::size_t n) const {
  const std::size_t first = inner_->firstInCollision(q, n);
  // The free ones, then the hit.
  record(q, std::min(first + 1, n), [&](std::size_t i) { return i == first; });
  return first;
}

void RecordingChecker::checkEach(const double* q, std::size_t n, std::uint8_t* out) const {
  inner_->inCollisionEach(q, n, out);
  record(q, n, [&](std::size_t i) { return out[i] != 0; });
}

CollisionChecker::MotionCheck RecordingChecker::checkMotion(const double* from, const double* to,
                                                            std::size_t segments) const {
  const MotionCheck answer = inner_->motionCollision(from, to, segments);
  if (answer.collidingState != 0) {
    std::vector<double> state(dof());
    motionState(from, to, dof(), answer.collidingState, segments, state.data());
    record(state.data(), 1, [](std::size_t) { return true; });
  }
  return answer;
}

Dataset RecordingChecker::take() {
  const std::lock_guard lock(mutex_);
  Dataset answers;
  answers.points = Eigen::Map<const Configurations>(
      values_.data(), static_cast<Eigen::Index>(labels_.size()), static_cast<Eigen::Index>(dof()));
  answers.labels = std::move(labels_);
  values_.clear();
  labels_.clear();
  return answers;
}

std::size_t RecordingChecker::recorded() const {
  const std::lock_guard lock(mutex_);
  return labels_.size();
}

CountedChecker::CountedChecker(std::shared_ptr<const CollisionChecker> inner)
    : inner_(std::move(inner)) {
  if (!inner_) throw InvalidArgument("CountedChecker: the checker is a null pointer");
}

bool CountedChecker::check(const double* q) const {
  return inner_->inCollision(std::span<const double>(q, dof()));
}

std::size_t CountedChecker::checkFirst(const double* q, std::size_t n) const {
  return inner_->firstInCollision(q, n);
}

void CountedChecker::checkEach(const double* q, std::size_t n, std::uint8_t* out) const {
  inner_->inCollisionEach(q, n, out);
}

CollisionChecker::MotionCheck CountedChecker::checkMotion(const double* from, const double* to,
                                                          std::size_t segments) const {
  return inner_->motionCollision(from, to, segments);
}

}  // namespace fastron
