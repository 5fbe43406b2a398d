#include "lane_kinematics.h"

#include <string>

#include "fastron/core/error.h"

namespace fastron::detail {

PlaceLanes placeLanesOf(SimdPath path) {
#ifdef FASTRON_SIMD_DISPATCH
  if (path == SimdPath::Avx2) return avx2::kPlaceLanes;
  if (path == SimdPath::Avx512) return avx512::kPlaceLanes;
#endif
  if (path == SimdPath::Portable) return portable::kPlaceLanes;
  throw InvalidArgument("this build has no SIMD path '" + std::string(toString(path)) + "'");
}

}  // namespace fastron::detail
