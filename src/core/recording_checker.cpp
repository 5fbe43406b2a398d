#include "fastron/core/recording_checker.h"

#include <algorithm>

#include "fastron/core/error.h"

namespace fastron {

RecordingChecker::RecordingChecker(std::shared_ptr<const CollisionChecker> inner)
    : inner_(std::move(inner)) {
  if (!inner_) throw InvalidArgument("RecordingChecker: the checker is a null pointer");
}

bool RecordingChecker::check(const double* q) const {
  return checkFirst(q, 1) == 0;
}

std::size_t RecordingChecker::checkFirst(const double* q, std::size_t n) const {
  const std::size_t dim = dof();
  const std::size_t first = inner_->firstInCollision(q, n);
  const std::size_t answered = std::min(first + 1, n);  // the free ones, then the hit
  const std::lock_guard lock(mutex_);
  values_.insert(values_.end(), q, q + answered * dim);
  for (std::size_t i = 0; i < answered; ++i) {
    labels_.push_back(i == first ? std::int8_t{1} : std::int8_t{-1});
  }
  return first;
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

}  // namespace fastron
