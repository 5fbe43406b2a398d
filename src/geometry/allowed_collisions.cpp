#include "fastron/geometry/allowed_collisions.h"

namespace fastron {

void AllowedCollisionMatrix::allow(const std::string& a, const std::string& b) {
  pairs_.emplace(std::min(a, b), std::max(a, b));
}

bool AllowedCollisionMatrix::allowed(std::string_view a, std::string_view b) const {
  return pairs_.count(a < b ? std::pair{std::string(a), std::string(b)}
                            : std::pair{std::string(b), std::string(a)}) > 0;
}

void AllowedCollisionMatrix::merge(const AllowedCollisionMatrix& other) {
  pairs_.insert(other.pairs_.begin(), other.pairs_.end());
}

}  // namespace fastron
