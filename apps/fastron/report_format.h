#pragma once
// Number formatting shared by the subcommands' printed tables.

#include <cmath>
#include <cstdio>
#include <string>

#include "fastron/experiments/common.h"  // seconds()

namespace fastron::cli {

/// A rate in [0, 1] as a fixed-point number, or "n/a" when undefined (NaN).
inline std::string rate(double value) {
  if (std::isnan(value)) return "n/a";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", value);
  return buffer;
}

/// A duration with a unit that keeps 3 significant digits: ns, us, ms or s.
inline std::string duration(double seconds) {
  char buffer[32];
  if (seconds < 1e-6) {
    std::snprintf(buffer, sizeof buffer, "%.0f ns", seconds * 1e9);
  } else if (seconds < 1e-3) {
    std::snprintf(buffer, sizeof buffer, "%.2f us", seconds * 1e6);
  } else if (seconds < 1) {
    std::snprintf(buffer, sizeof buffer, "%.2f ms", seconds * 1e3);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.2f s", seconds);
  }
  return buffer;
}

/// A speed ratio such as "3.4x".
inline std::string times(double ratio) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1fx", ratio);
  return buffer;
}

}  // namespace fastron::cli
