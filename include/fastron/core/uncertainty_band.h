#pragma once
// The uncertainty band of a model's score: where the model's answer is trusted, and where an
// exact checker must answer instead (a hybrid checker, as DiffCo's). Calibrated on labelled
// configurations the model was not trained on, to a target rate of colliding configurations the
// model would answer "free".

#include <Eigen/Core>
#include <cstddef>

#include "fastron/core/export.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

/// Scores below `lower` are answered "free" from the model, scores above `upper` "in collision";
/// scores in [lower, upper] go to the exact checker. lower <= 0 <= upper.
struct UncertaintyBand {
  double lower = 0;
  double upper = 0;
  bool contains(double score) const { return score >= lower && score <= upper; }
};

/// What a calibration aims at, as rates among held-out configurations.
struct BandTargets {
  /// Colliding configurations answered "free" by the model at most (the safety target).
  double missRate = 0.005;
  /// Free configurations answered "in collision" by the model at most: a false alarm closes a
  /// passage for the planner, but costs no correctness; 1 keeps the model's own boundary above.
  double falseAlarmRate = 0.05;
};

/// Throws InvalidArgument naming the field outside [0, 1].
void validate(const BandTargets& targets);

/// A calibration and what it saw.
struct BandCalibration {
  UncertaintyBand band;
  std::size_t colliding = 0;  ///< held-out configurations in collision
  std::size_t free = 0;       ///< held-out configurations free
  double modelMissRate = 0;   ///< of the colliding ones, the share the model (sign) calls free
  double bandMissRate = 0;    ///< the share scored below band.lower
  double exactShare = 0;      ///< of all held-out ones, the share inside the band
};

/// The narrowest band meeting `targets` on these held-out scores and labels (+1 / -1): lower is
/// the k-th smallest colliding score with k = floor(missRate * colliding) (so at most k colliding
/// configurations lie below it), upper likewise from the free scores; each is clamped to the
/// model's own boundary 0. Without colliding (free) configurations, lower (upper) stays 0: no
/// evidence, the model's own answer. Throws InvalidArgument on mismatched sizes, a label other
/// than +1 / -1 or a non-finite score.
BandCalibration calibrateBand(const Eigen::VectorXd& scores, const Labels& labels,
                              const BandTargets& targets = {});

}  // namespace fastron
