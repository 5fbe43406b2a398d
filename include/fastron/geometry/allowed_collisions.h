#pragma once
// Pairs of robot links allowed to touch: self-collision checks skip them (MoveIt's
// allowed_collision_matrix plays the same role).

#include <set>
#include <string>
#include <string_view>
#include <utility>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

class AllowedCollisionMatrix {
 public:
  void allow(const std::string& a, const std::string& b);
  bool allowed(std::string_view a, std::string_view b) const;
  void merge(const AllowedCollisionMatrix& other);
  std::size_t size() const { return pairs_.size(); }

 private:
  std::set<std::pair<std::string, std::string>> pairs_;  // (smaller, larger) name
};

}  // namespace fastron
