#pragma once
// The batched positions of RobotPointKinematics, compiled once per SimdPath
// (lane_kinematics_portable.cpp, lane_kinematics_avx2.cpp, lane_kinematics_avx512.cpp) like the
// kernel sums of core. Private to geometry.

#include <cstddef>

#include "fastron/geometry/detail/lane_chain.h"
#include "internal/simd_dispatch.h"

namespace fastron::detail {

/// Float positions of `count` configurations (rows of q, chain.dof values each), the lanes of a
/// register computed together: `out` gets 3 * chain.pointCount values per configuration.
using PlaceLanes = void (*)(const LaneChain& chain, const double* q, std::size_t count, float* out);

namespace portable {
extern const PlaceLanes kPlaceLanes;
}
namespace avx2 {
extern const PlaceLanes kPlaceLanes;
}
namespace avx512 {
extern const PlaceLanes kPlaceLanes;
}

/// The function of the path in use (through activeSimdPath(): the atomic of core's inline
/// currentSimdPath is not exported; one call per batch of up to sixteen configurations).
inline PlaceLanes activePlaceLanes() {
  return ofSimdPath(activeSimdPath(), portable::kPlaceLanes, avx2::kPlaceLanes,
                    avx512::kPlaceLanes);
}

}  // namespace fastron::detail
