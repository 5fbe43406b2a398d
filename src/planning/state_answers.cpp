#include "fastron/planning/state_answers.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

#include "fastron/core/error.h"

namespace fastron {
namespace {

/// splitmix64's finaliser: every bit of x moves about half of the result's bits.
std::uint64_t mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

StateAnswers::StateAnswers(std::size_t dim, std::size_t slots) : dim_(dim), slots_(slots) {
  if (dim == 0) throw InvalidArgument("StateAnswers: the dimension must be positive");
  if (slots == 0) throw InvalidArgument("StateAnswers: the number of slots must be positive");
}

std::size_t StateAnswers::slotOf(const double* q) const {
  std::uint64_t h = 0;
  for (std::size_t j = 0; j < dim_; ++j) h = mix(h ^ std::bit_cast<std::uint64_t>(q[j]));
  return static_cast<std::size_t>(h % slots_);
}

std::optional<bool> StateAnswers::find(const double* q) const {
  const std::size_t slot = slotOf(q);
  const std::lock_guard lock(mutex_);
  if (answers_.empty() || answers_[slot] == Slot::Empty ||
      std::memcmp(values_.data() + slot * dim_, q, dim_ * sizeof(double)) != 0) {
    return std::nullopt;
  }
  return answers_[slot] == Slot::Collides;
}

void StateAnswers::remember(const double* q, bool collides) {
  const std::size_t slot = slotOf(q);
  const std::lock_guard lock(mutex_);
  if (answers_.empty()) {
    // Not in the constructor: a validator of a plan that never asks costs nothing.
    values_.resize(slots_ * dim_);
    answers_.assign(slots_, Slot::Empty);
  }
  std::copy_n(q, dim_, values_.data() + slot * dim_);
  answers_[slot] = collides ? Slot::Collides : Slot::Free;
}

}  // namespace fastron
