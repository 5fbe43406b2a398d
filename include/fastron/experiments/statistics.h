#pragma once
// Summaries of measured values (mean, standard deviation, median) and their text.

#include <string>
#include <vector>

namespace fastron::experiments {

struct Summary {
  double mean = 0, stddev = 0;
  std::size_t count = 0;
  double median = 0;
};
/// Mean, sample standard deviation and median, ignoring NaN values.
Summary summarize(const std::vector<double>& values);
/// "12.3 ± 4.5" with `digits` decimals ("12.3" for a single value).
std::string meanStd(const Summary& s, int digits);
/// A duration in seconds as "mean ± std unit" with a unit chosen for the mean (ns, µs, ms, s).
std::string durationMeanStd(const Summary& seconds);
/// One duration in seconds with the unit durationMeanStd would choose, e.g. "2.14 µs".
std::string durationText(double seconds);

}  // namespace fastron::experiments
