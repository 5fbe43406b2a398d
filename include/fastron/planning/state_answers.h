#pragma once
// What a collision source answered about configurations it was asked before, by their exact joint
// values: a planner asks about the same states again and again. RRT-Connect checks a motion of
// its goal tree from the new state towards the tree's node, so every extension from a node checks
// that node once more, and OMPL's simplifier checks the path's waypoints once per shortcut that
// ends there. In the generated cage family a third of the exact checks of a hybrid's plans were
// such repeats (one goal, asked 13,610 times over twenty requests).

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// A fixed-size cache of answers keyed by configuration (bit for bit equal joint values; -0 and
/// +0 are different keys, which only costs a miss). Direct-mapped: a new answer replaces the one
/// whose slot it hashes to, so it holds at most `slots` answers, the most recent ones, and never
/// allocates after its first answer. Safe to use from many threads.
class StateAnswers {
 public:
  /// Throws InvalidArgument when dim or slots is 0.
  explicit StateAnswers(std::size_t dim, std::size_t slots = 2048);

  /// Whether `q` (dim values) collides, when it was remembered and not replaced since.
  std::optional<bool> find(const double* q) const;
  /// Remembers that `q` collides (true) or is free (false).
  void remember(const double* q, bool collides);

  std::size_t dim() const { return dim_; }

 private:
  enum class Slot : std::uint8_t { Empty, Free, Collides };
  std::size_t slotOf(const double* q) const;

  std::size_t dim_;
  std::size_t slots_;
  mutable std::mutex mutex_;
  std::vector<double> values_;  ///< slots_ x dim_, allocated with the first answer
  std::vector<Slot> answers_;
};

}  // namespace fastron
