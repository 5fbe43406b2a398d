#pragma once
// The run-time choice among code compiled once per SimdPath (simd.h): each such file defines its
// object in namespace portable, avx2 or avx512 (fastron_simd_sources in src/CMakeLists.txt), and
// the callers pick one with ofSimdPath(currentSimdPath(), ...). Private to the library.

#include <atomic>

#include "fastron/core/simd.h"

namespace fastron::detail {

/// The path in use, as an int; -1 until the first query or useSimdPath chooses one (simd.cpp).
extern std::atomic<int> activeSimdPathIndex;
/// First use: the path FASTRON_SIMD asks for, else the widest this processor runs, made the
/// path in use.
SimdPath chooseSimdPath();

/// The path in use: one atomic load, inline on core's hot paths (activeSimdPath() is this, out of
/// line). Not for other layers: the atomic is not exported from the shared library.
inline SimdPath currentSimdPath() {
  const int path = activeSimdPathIndex.load(std::memory_order_acquire);
  return path >= 0 ? static_cast<SimdPath>(path) : chooseSimdPath();
}

/// The object of `path` among the three compiled per path.
template <class T>
const T& ofSimdPath(SimdPath path, const T& portable, const T& avx2, const T& avx512) {
  switch (path) {
    case SimdPath::Avx2:
      return avx2;
    case SimdPath::Avx512:
      return avx512;
    case SimdPath::Portable:
      break;
  }
  return portable;
}

}  // namespace fastron::detail
