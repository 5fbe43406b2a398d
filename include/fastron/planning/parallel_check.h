#pragma once
// The exact check of a whole path, for verification: on every core, in an order that finds
// collisions early.

#include "fastron/core/export.h"
#include "fastron/planning/motion.h"

namespace FASTRON_API fastron {

/// The same answer as checkPath (every invalid waypoint and edge), computed on `threads` threads
/// (0: the first 16 states on the calling thread, timed, and the rest on every core when at that
/// rate they would take 250 us or more, else on the calling thread too: a worker's wake-up and
/// cold caches pay on the mesh Panda's paths, not on a few hundred checks of a microsecond) in a
/// global bisection order: the waypoints first, then every edge's midpoint, then its quarter
/// points, and so on across the whole path, so that a colliding stretch is found after a few
/// checks wherever it lies. An edge stops being checked at its first collision. `checker` must be
/// safe to call from many threads (every CollisionChecker of Fastron is). A checker that proves
/// motions free (CollisionChecker::provesMotionsFree) gets the first waypoint and then whole edges
/// (motionCollision, each deciding its end waypoint), one edge at a time per thread. Throws
/// InvalidArgument on waypoints of the wrong dimension, and rethrows the first exception a check
/// throws.
PathCheck checkPathParallel(const CollisionChecker& checker, const JointPath& path,
                            double resolution, unsigned threads = 0);

}  // namespace fastron
