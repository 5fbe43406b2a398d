#pragma once
// Parallel labelling of configurations by an exact collision checker: the labelling dominates
// the update time (paper, Sec. IV-B), so it runs on every core.

#include <chrono>
#include <cstddef>
#include <stop_token>

#include "fastron/core/collision_checker.h"
#include "fastron/core/error.h"
#include "fastron/core/export.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

/// How far labelConfigurations trusts its oracle.
struct LabelGuard {
  /// No checker call starts after this moment; one that would throws OracleFault.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  /// Rows (evenly spread) whose label is asked twice; two different answers throw OracleFault.
  /// The second call follows the call that answered the row (a run of at most 16 rows), so a
  /// scene changed between them is rare, and would make the labels inconsistent anyway.
  std::size_t repeatedRows = 0;
  /// Stops the labelling between checker calls (throws LabellingStopped).
  std::stop_token stop;
};

/// Thrown by labelConfigurations when its guard's stop was requested.
class LabellingStopped : public Error {
 public:
  using Error::Error;
};

/// +1 / -1 label of every row of q (joint values). `threads` = 0 uses every hardware thread. The
/// rows go out in chunks of 16; a chunk's first row is one call of the checker and, when that
/// call took under 20 us, the other rows are one more (CollisionChecker::inCollisionEach: one
/// read of the world and one scratch for all), else one call each. The guard is looked at before
/// each call. A checker call that throws, the deadline or a repeated row answered both ways
/// throws OracleFault naming the checker (with the checker's own message), once every thread
/// has stopped.
Labels labelConfigurations(const CollisionChecker& checker, const Configurations& q,
                           unsigned threads = 0, const LabelGuard& guard = {});

}  // namespace fastron
