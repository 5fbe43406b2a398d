#pragma once
// Parallel labelling of configurations by an exact collision checker: the labelling dominates
// the update time (paper, Sec. IV-B), so it runs on every core.

#include "fastron/core/collision_checker.h"
#include "fastron/core/export.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

/// +1 / -1 label of every row of q (joint values). `threads` = 0 uses every hardware thread.
/// Rethrows the first exception a checker call threw.
Labels labelConfigurations(const CollisionChecker& checker, const Configurations& q,
                           unsigned threads = 0);

}  // namespace fastron
