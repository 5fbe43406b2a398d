#include "fastron/experiments/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace fastron::experiments {

Summary summarize(const std::vector<double>& values) {
  Summary s;
  double sum = 0, squares = 0;
  for (const double v : values) {
    if (std::isnan(v)) continue;
    sum += v;
    ++s.count;
  }
  if (s.count == 0) return {std::nan(""), std::nan(""), 0, std::nan("")};
  s.mean = sum / static_cast<double>(s.count);
  for (const double v : values) {
    if (!std::isnan(v)) squares += (v - s.mean) * (v - s.mean);
  }
  s.stddev = s.count > 1 ? std::sqrt(squares / static_cast<double>(s.count - 1)) : 0.0;
  std::vector<double> sorted;
  sorted.reserve(s.count);
  for (const double v : values) {
    if (!std::isnan(v)) sorted.push_back(v);
  }
  std::sort(sorted.begin(), sorted.end());
  const std::size_t middle = sorted.size() / 2;
  s.median = sorted.size() % 2 ? sorted[middle] : 0.5 * (sorted[middle - 1] + sorted[middle]);
  return s;
}

std::string meanStd(const Summary& s, int digits) {
  if (s.count == 0) return "n/a";
  char buffer[64];
  if (s.count == 1) {  // one value has no spread to report
    std::snprintf(buffer, sizeof buffer, "%.*f", digits, s.mean);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.*f ± %.*f", digits, s.mean, digits, s.stddev);
  }
  return buffer;
}

namespace {

struct Unit {
  double scale;
  const char* name;
  int digits;  // decimals: 2 below 10 units, 1 above
};

Unit unitFor(double seconds) {
  const auto unit = [&](double scale, const char* name) {
    return Unit{scale, name, seconds * scale < 10 ? 2 : 1};
  };
  return seconds < 1e-6   ? unit(1e9, "ns")
         : seconds < 1e-3 ? unit(1e6, "µs")
         : seconds < 1    ? unit(1e3, "ms")
                          : unit(1, "s");
}

}  // namespace

std::string durationMeanStd(const Summary& seconds) {
  if (seconds.count == 0) return "n/a";
  const Unit unit = unitFor(seconds.mean);
  return meanStd({seconds.mean * unit.scale, seconds.stddev * unit.scale, seconds.count},
                 unit.digits) +
         " " + unit.name;
}

std::string durationText(double seconds) {
  const Unit unit = unitFor(seconds);
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f %s", unit.digits, seconds * unit.scale, unit.name);
  return buffer;
}

}  // namespace fastron::experiments
