#include "fastron/core/simd.h"

#include <atomic>
#include <cstdlib>
#include <string>

#include "fastron/core/error.h"
#include "internal/simd_dispatch.h"

namespace fastron {
namespace {

/// Whether this processor can run `path` as built. FASTRON_SIMD_X86: the per-path files were
/// compiled for their x86-64 instruction sets (src/CMakeLists.txt); elsewhere all three hold
/// portable code, and only the portable path is offered.
bool processorRuns(SimdPath path) {
#ifdef FASTRON_SIMD_X86
  __builtin_cpu_init();
  // The instruction sets the *_avx2.cpp and *_avx512.cpp files are compiled for.
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  switch (path) {
    case SimdPath::Portable:
      return true;
    case SimdPath::Avx2:
      return avx2;
    case SimdPath::Avx512:
      return avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
  }
  return false;
#else
  return path == SimdPath::Portable;
#endif
}

std::string namesOf(const std::vector<SimdPath>& paths) {
  std::string names;
  for (const SimdPath path : paths)
    names += (names.empty() ? "" : ", ") + std::string(toString(path));
  return names;
}

}  // namespace

std::string_view toString(SimdPath path) {
  switch (path) {
    case SimdPath::Avx2:
      return "avx2";
    case SimdPath::Avx512:
      return "avx512";
    case SimdPath::Portable:
      break;
  }
  return "portable";
}

SimdPath parseSimdPath(std::string_view name) {
  for (const SimdPath path : {SimdPath::Portable, SimdPath::Avx2, SimdPath::Avx512}) {
    if (name == toString(path)) return path;
  }
  throw InvalidArgument("unknown SIMD path '" + std::string(name) +
                        "' (expected 'portable', 'avx2' or 'avx512')");
}

std::vector<SimdPath> supportedSimdPaths() {
  std::vector<SimdPath> paths{SimdPath::Portable};
  for (const SimdPath path : {SimdPath::Avx2, SimdPath::Avx512}) {
    if (processorRuns(path)) paths.push_back(path);
  }
  return paths;
}

SimdPath simdPathFor(const char* request) {
  const std::vector<SimdPath> supported = supportedSimdPaths();
  if (request == nullptr || *request == '\0') return supported.back();
  SimdPath path{};
  try {
    path = parseSimdPath(request);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(std::string("FASTRON_SIMD: ") + e.what());
  }
  if (!processorRuns(path)) {
    throw InvalidArgument(
        "FASTRON_SIMD=" + std::string(request) +
        ": this processor or build cannot run it (supported: " + namesOf(supported) + ")");
  }
  return path;
}

void useSimdPath(SimdPath path) {
  if (!processorRuns(path)) {
    throw InvalidArgument("this processor or build cannot run the SIMD path '" +
                          std::string(toString(path)) +
                          "' (supported: " + namesOf(supportedSimdPaths()) + ")");
  }
  detail::activeSimdPathIndex.store(static_cast<int>(path), std::memory_order_release);
}

SimdPath activeSimdPath() {
  return detail::currentSimdPath();
}

namespace detail {
std::atomic<int> activeSimdPathIndex{-1};

SimdPath chooseSimdPath() {
  // Two threads may both get here; they choose the same path.
  const SimdPath chosen = simdPathFor(std::getenv("FASTRON_SIMD"));
  useSimdPath(chosen);
  return chosen;
}
}  // namespace detail
}  // namespace fastron
