#pragma once
// What the subcommands print alike: rates, ratios and progress lines. (Durations: durationText,
// shared with the experiments' reports.)

#include <cmath>
#include <cstdio>
#include <string>

#include <chrono>
#include <iostream>
#include <string_view>

#include "fastron/experiments/progress.h"
#include "fastron/experiments/statistics.h"  // Progress, durationText()

namespace fastron::cli {

using experiments::durationText;

/// A rate in [0, 1] as a fixed-point number, or "n/a" when undefined (NaN).
inline std::string rate(double value) {
  if (std::isnan(value)) return "n/a";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", value);
  return buffer;
}

/// A speed ratio such as "3.4x".
inline std::string times(double ratio) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1fx", ratio);
  return buffer;
}

/// The progress printer of every long-running command: "[12 s] line", seconds since it was made.
inline experiments::Progress progressPrinter() {
  const auto start = std::chrono::steady_clock::now();
  return [start](std::string_view line) {
    const double s = inSeconds(std::chrono::steady_clock::now() - start);
    std::cout << "[" << static_cast<int>(s) << " s] " << line << std::endl;
  };
}

}  // namespace fastron::cli
