#pragma once
// Which SIMD instructions the library's hot loops run on, chosen when the program runs.
//
// The kernel sums of every `Model` query, the batched control-point positions
// (`RobotPointKinematics::positionsBatch`, every edge check on a task-space model) and the two
// passes of each Algorithm 1 iteration are compiled three times, for plain x86-64 (SSE2), for
// AVX2 with FMA and for AVX-512, and the library picks the widest this processor supports, so a
// binary built on one x86-64 machine runs on any other (a portable build: FASTRON_NATIVE=OFF).
// On other processors there is one path, `portable`. The environment variable FASTRON_SIMD
// (`portable`, `avx2`, `avx512`) or `useSimdPath` chooses another, to compare them.

#include <cstdint>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

enum class SimdPath : std::uint8_t {
  Portable = 0,  ///< the compiler's baseline for the target (SSE2 on x86-64)
  Avx2 = 1,      ///< AVX2 and FMA: 8 floats per instruction
  Avx512 = 2,    ///< AVX-512 (F, BW, DQ, VL): 16 floats per instruction
};

/// "portable", "avx2" or "avx512".
std::string_view toString(SimdPath path);
/// Parses a name of toString; throws InvalidArgument naming the value.
SimdPath parseSimdPath(std::string_view name);

/// The paths this build has and this processor can run, narrowest first.
std::vector<SimdPath> supportedSimdPaths();

/// The path queries use now: the one set by useSimdPath, else the one FASTRON_SIMD names, else
/// the widest supported. Throws InvalidArgument when FASTRON_SIMD names an unknown path or one
/// this processor cannot run (and so does every query, until useSimdPath chooses one).
SimdPath activeSimdPath();

/// Makes every query in the process use `path` from now on (queries under way finish on the
/// path they started on). Throws InvalidArgument when this processor cannot run it.
void useSimdPath(SimdPath path);

/// The path a FASTRON_SIMD value asks for: the widest supported when `request` is null or
/// empty. Throws InvalidArgument, naming the variable and the value, when it is unknown or not
/// supported here.
SimdPath simdPathFor(const char* request);

}  // namespace fastron
