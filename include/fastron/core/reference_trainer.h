#pragma once
// Algorithm 1 written as plainly as it can be: the baseline the optimised Trainer is measured
// against in the same benchmark run, and the reference its results are tested against.

#include <Eigen/Core>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/trainer.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

struct ReferenceTraining {
  std::vector<double> alpha;  ///< weight of every training point
  std::vector<double> f;      ///< F = K alpha at every training point
  UpdateReport report;        ///< iterations, stop reason, revert, misclassified, support count
};

/// Algorithm 1 on features `x` (one row per point) with labels `y` (+1 / -1), from zero weights:
/// the same greedy updates, conditional bias, support cap, redundant-point removal and revert
/// safeguard as Trainer::update, in double, one value at a time (its file is compiled without
/// auto-vectorisation), each Gram column computed afresh. Throws InvalidArgument on mismatched
/// sizes or a label other than +1 / -1.
ReferenceTraining trainReference(const Eigen::MatrixXd& x, const Labels& y,
                                 const TrainParams& params);

}  // namespace fastron
