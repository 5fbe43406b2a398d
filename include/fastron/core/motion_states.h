#pragma once
// The states a straight joint motion is checked at: the one discretisation every planner,
// verifier, checker and test of Fastron shares.

#include <cstddef>
#include <vector>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// Number of equal segments a motion from a to b (`dim` values each) is checked in:
/// ceil(|b - a| / resolution), at least 1, so no two consecutive checked states are more than
/// `resolution` apart (Euclidean distance in joint units, as OMPL's RealVectorStateSpace measures
/// it). Throws InvalidArgument when resolution is not positive.
std::size_t segmentCount(const double* a, const double* b, std::size_t dim, double resolution);

/// State i of n of the motion from a to b: a + (b - a) i / n, and b itself for i = n (the sum
/// may round off it). Writes `dim` values to `out`.
void motionState(const double* a, const double* b, std::size_t dim, std::size_t i, std::size_t n,
                 double* out);

/// The index i (1..n) of motionStates' row `row` (< n): n for row 0, then the odd multiples of
/// the largest power of two below n, and so on down to the odd numbers.
std::size_t bisectionIndex(std::size_t n, std::size_t row);

/// The states a + (b - a) i / n for i = 1..n (b included, a not: a motion starts at a state
/// already known to be valid), in bisection order: b first, then the midpoint, then the quarter
/// points, and so on (bisectionIndex), because a collision is found soonest that way. Written row
/// by row into `out` (n * dim values, resized).
void motionStates(const double* a, const double* b, std::size_t dim, std::size_t n,
                  std::vector<double>& out);

}  // namespace fastron
