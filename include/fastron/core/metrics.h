#pragma once
// Classification metrics of the paper: accuracy, true positive rate, true negative rate.

#include <cstddef>
#include <span>

#include "fastron/core/export.h"
#include "fastron/core/model.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

/// Confusion counts with the in-collision class (+1) as "positive".
struct ConfusionCounts {
  std::size_t truePositives = 0, trueNegatives = 0, falsePositives = 0, falseNegatives = 0;

  void add(bool predictedCollision, bool actualCollision);
  std::size_t total() const;
  double accuracy() const;  ///< NaN when empty
  double tpr() const;       ///< in-collision samples classified as such; NaN with no positives
  double tnr() const;       ///< free samples classified as such; NaN with no negatives
};

/// The counts of predicted(i) (true: in collision) against labels[i] for every i: the one place
/// predictions are counted.
template <class Predicted>
ConfusionCounts confusionOf(std::span<const std::int8_t> labels, const Predicted& predicted) {
  ConfusionCounts counts;
  for (std::size_t i = 0; i < labels.size(); ++i) counts.add(predicted(i), labels[i] > 0);
  return counts;
}

/// Compares the model's predictions with the labels of `q` (joint values, one per row).
ConfusionCounts evaluate(const Model& model, const Configurations& q,
                         std::span<const std::int8_t> labels);

}  // namespace fastron
