#include "fastron/core/uncertainty_band.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "fastron/core/error.h"

namespace fastron {
namespace {

void checkRate(double rate, const char* field) {
  if (!(rate >= 0 && rate <= 1)) {
    throw InvalidArgument(std::string("BandTargets::") + field + " must be in [0, 1], got " +
                          std::to_string(rate));
  }
}

/// The k-th value of `values` in the order `before` (k = floor(rate * size)), or `none` when empty.
template <class Before>
double kthValue(std::vector<double>& values, double rate, double none, Before before) {
  if (values.empty()) return none;
  const auto k =
      std::min(values.size() - 1,
               static_cast<std::size_t>(std::floor(rate * static_cast<double>(values.size()))));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end(),
                   before);
  return values[k];
}

}  // namespace

void validate(const BandTargets& targets) {
  checkRate(targets.missRate, "missRate");
  checkRate(targets.falseAlarmRate, "falseAlarmRate");
}

BandCalibration calibrateBand(const Eigen::VectorXd& scores, const Labels& labels,
                              const BandTargets& targets) {
  validate(targets);
  if (static_cast<std::size_t>(scores.size()) != labels.size()) {
    throw InvalidArgument("calibrateBand: " + std::to_string(scores.size()) + " scores but " +
                          std::to_string(labels.size()) + " labels");
  }
  std::vector<double> colliding, free;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const double s = scores[static_cast<Eigen::Index>(i)];
    if (!std::isfinite(s)) {
      throw InvalidArgument("calibrateBand: score " + std::to_string(i) + " is not finite");
    }
    if (labels[i] == 1) {
      colliding.push_back(s);
    } else if (labels[i] == -1) {
      free.push_back(s);
    } else {
      throw InvalidArgument("calibrateBand: label " + std::to_string(i) + " is " +
                            std::to_string(labels[i]) + ", not +1 or -1");
    }
  }
  BandCalibration c;
  c.colliding = colliding.size();
  c.free = free.size();
  // With k = floor(rate * n), at most k values lie strictly beyond the k-th one.
  c.band.lower = std::min(0.0, kthValue(colliding, targets.missRate, 0.0, std::less<>{}));
  c.band.upper = std::max(0.0, kthValue(free, targets.falseAlarmRate, 0.0, std::greater<>{}));

  std::size_t modelMisses = 0, bandMisses = 0, inBand = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const double s = scores[static_cast<Eigen::Index>(i)];
    if (labels[i] == 1 && s <= 0) ++modelMisses;
    if (labels[i] == 1 && s < c.band.lower) ++bandMisses;
    if (c.band.contains(s)) ++inBand;
  }
  const auto share = [](std::size_t part, std::size_t whole) {
    return whole == 0 ? 0.0 : static_cast<double>(part) / static_cast<double>(whole);
  };
  c.modelMissRate = share(modelMisses, c.colliding);
  c.bandMissRate = share(bandMisses, c.colliding);
  c.exactShare = share(inBand, labels.size());
  return c;
}

}  // namespace fastron
