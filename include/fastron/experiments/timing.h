#pragma once
// Time per query of a checker or a model, and clearances, measured over configurations.

#include <functional>
#include <vector>
#include "fastron/core/collision_checker.h"
#include "fastron/core/types.h"
#include "fastron/geometry/scene_checker.h"

namespace fastron::experiments {

/// Mean seconds per exact check of each row of q (a checker's inCollision).
double meanSecondsPerCheck(const Configurations& q, const CollisionChecker& checker,
                           double minSeconds = 0.05);

/// Each row's distance to the nearest obstacle under `exact` (0 for one in collision), on every
/// core: between meshes a distance takes milliseconds (about 3 ms on the mesh Panda).
std::vector<double> clearances(const SceneChecker& exact, const Configurations& q);

/// Mean seconds per call of `fn` on each row of q, over at least `minSeconds` (whole passes).
double meanSecondsPerCall(const Configurations& q, const std::function<bool(const double*)>& fn,
                          double minSeconds = 0.05);

}  // namespace fastron::experiments
