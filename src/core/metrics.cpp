#include "fastron/core/metrics.h"

#include <limits>
#include <string>

#include "fastron/core/error.h"

namespace fastron {
namespace {

double ratio(std::size_t numerator, std::size_t denominator) {
  return denominator == 0 ? std::numeric_limits<double>::quiet_NaN()
                          : static_cast<double>(numerator) / static_cast<double>(denominator);
}

}  // namespace

void ConfusionCounts::add(bool predictedCollision, bool actualCollision) {
  if (actualCollision) {
    ++(predictedCollision ? truePositives : falseNegatives);
  } else {
    ++(predictedCollision ? falsePositives : trueNegatives);
  }
}

std::size_t ConfusionCounts::total() const {
  return truePositives + trueNegatives + falsePositives + falseNegatives;
}
double ConfusionCounts::accuracy() const {
  return ratio(truePositives + trueNegatives, total());
}
double ConfusionCounts::tpr() const {
  return ratio(truePositives, truePositives + falseNegatives);
}
double ConfusionCounts::tnr() const {
  return ratio(trueNegatives, trueNegatives + falsePositives);
}

ConfusionCounts evaluate(const Model& model, const Configurations& q,
                         std::span<const std::int8_t> labels) {
  if (static_cast<std::size_t>(q.rows()) != labels.size()) {
    throw InvalidArgument(std::to_string(q.rows()) + " configurations but " +
                          std::to_string(labels.size()) + " labels");
  }
  const Eigen::VectorXd scores = model.scoreBatch(q);
  return confusionOf(labels,
                     [&](std::size_t i) { return scores[static_cast<Eigen::Index>(i)] > 0; });
}

}  // namespace fastron
