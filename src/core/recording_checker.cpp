#include "fastron/core/recording_checker.h"

#include "fastron/core/error.h"

namespace fastron {

RecordingChecker::RecordingChecker(std::shared_ptr<const CollisionChecker> inner)
    : inner_(std::move(inner)) {
  if (!inner_) throw InvalidArgument("RecordingChecker: the checker is a null pointer");
}

bool RecordingChecker::check(const double* q) const {
  const std::size_t dim = dof();
  const bool hit = inner_->inCollision(std::span<const double>(q, dim));
  const std::lock_guard lock(mutex_);
  values_.insert(values_.end(), q, q + dim);
  labels_.push_back(hit ? std::int8_t{1} : std::int8_t{-1});
  return hit;
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
