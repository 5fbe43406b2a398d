#pragma once
// The exact check of a whole path, for verification: on every core, in an order that finds
// collisions early.

#include "fastron/core/export.h"
#include "fastron/planning/motion.h"

namespace FASTRON_API fastron {

/// The same answer as checkPath (every invalid waypoint and edge), computed on `threads` threads
/// (0: every core for paths of 1024 states or more, where it pays even with cold caches; shorter
/// ones on the calling thread) in a global bisection order: the waypoints first, then every edge's
/// midpoint, then its quarter points, and so on across the whole path, so that a colliding stretch
/// is found after a few checks wherever it lies. An edge stops being checked at its first
/// collision. `checker` must be safe to call from many threads (every CollisionChecker of Fastron
/// is). Throws InvalidArgument on waypoints of the wrong dimension, and rethrows the first
/// exception a check throws.
PathCheck checkPathParallel(const CollisionChecker& checker, const JointPath& path,
                            double resolution, unsigned threads = 0);

}  // namespace fastron
