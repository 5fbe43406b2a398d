#pragma once
// Random worlds of cubes for the static experiments.

#include <cstddef>
#include "fastron/core/types.h"
#include "fastron/geometry/scene.h"

namespace fastron::experiments {

/// Up to `maxCubes` cubes (at least one) of random size in [minSide, maxSide], centred in the
/// upper half of the ball of radius `reach` around the robot's base, and clear of the base.
Scene randomCubes(std::size_t maxCubes, double minSide, double maxSide, double reach, Rng& rng);

}  // namespace fastron::experiments
