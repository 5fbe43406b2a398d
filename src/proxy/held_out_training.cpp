#include "fastron/proxy/held_out_training.h"

#include <algorithm>
#include <string>

#include "fastron/core/active_learning.h"
#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/proxy/labelling.h"

namespace fastron {

void validate(const HeldOutTargets& targets) {
  const auto checkRate = [](double value, const char* name) {
    if (!(value >= 0 && value <= 1)) {
      throw InvalidArgument(std::string(name) + " must be in [0, 1], got " + std::to_string(value));
    }
  };
  checkRate(targets.accuracy, "target accuracy");
  checkRate(targets.truePositiveRate, "target TPR");
  if (targets.samplesPerRound == 0) {
    throw InvalidArgument("held-out samples per round must be at least 1");
  }
}

namespace {

/// How far `counts` fall short of the targets: 0 when they meet them.
double shortfall(const ConfusionCounts& counts, const HeldOutTargets& targets) {
  // A scene without colliding configurations has no TPR to miss.
  const bool noPositives = counts.truePositives + counts.falseNegatives == 0;
  const double tprShort = noPositives ? 0 : std::max(0.0, targets.truePositiveRate - counts.tpr());
  return std::max(0.0, targets.accuracy - counts.accuracy()) + tprShort;
}

}  // namespace

HeldOutTraining trainToHeldOutTargets(const CollisionChecker& oracle, const FeatureMap& features,
                                      const TrainParams& params, std::size_t initialSamples,
                                      const HeldOutTargets& targets, Rng& rng, unsigned threads,
                                      std::span<const CollisionChecker* const> grownOracles,
                                      std::span<const ModelCandidate> alternatives) {
  validate(targets);
  if (initialSamples == 0) throw InvalidArgument("initial samples must be at least 1");
  for (const ModelCandidate& alternative : alternatives) {
    if (alternative.features.configurationDim() != features.configurationDim()) {
      throw InvalidArgument("an alternative feature map reads " +
                            std::to_string(alternative.features.configurationDim()) +
                            " joint values, the first " +
                            std::to_string(features.configurationDim()));
    }
    validate(alternative.params);
  }
  for (const CollisionChecker* grown : grownOracles) {
    if (grown == nullptr) throw InvalidArgument("a grown oracle is null");
    if (grown->dof() != oracle.dof()) {
      throw InvalidArgument("a grown oracle has " + std::to_string(grown->dof()) +
                            " joints, the oracle " + std::to_string(oracle.dof()));
    }
  }
  std::size_t level = 0;  // whose labels the rounds learn: 0 oracle, k grownOracles[k - 1]
  const auto labelsAt = [&](std::size_t at, const Eigen::MatrixXd& points) {
    return labelConfigurations(at == 0 ? oracle : *grownOracles[at - 1], points, threads);
  };
  Dataset learned;
  learned.points = uniformConfigurations(features.limits(), initialSamples, rng);
  learned.labels = labelsAt(level, learned.points);

  HeldOutTraining result;
  double bestShortfall = 0;
  Dataset fresh;
  // Algorithm 1 from zero weights on every configuration learned so far with candidate k's
  // features and parameters, measured on `fresh`; the closest to the targets is kept.
  const auto trainAndMeasure = [&](std::size_t k) {
    Trainer trainer(k == 0 ? features : alternatives[k - 1].features,
                    k == 0 ? params : alternatives[k - 1].params);
    trainer.addPoints(learned.points, learned.labels);
    const UpdateReport update = trainer.update(threads);
    const std::shared_ptr<const Model> model = trainer.model();
    const ConfusionCounts counts = evaluate(*model, fresh.points, fresh.labels);
    result.rounds.push_back({learned.size(), model->supportCount(), counts, level, k});
    const double missing = shortfall(counts, targets);
    if (!result.model || missing < bestShortfall) {
      result.model = model;
      result.chosenRound = result.rounds.size() - 1;
      result.update = update;
      bestShortfall = missing;
    }
    return update;
  };
  for (;;) {
    fresh.points = uniformConfigurations(features.limits(), targets.samplesPerRound, rng);
    fresh.labels = labelsAt(0, fresh.points);
    const UpdateReport update = trainAndMeasure(0);
    const ConfusionCounts counts = result.rounds.back().heldOut;  // a copy: rounds grows below
    // No round before this one met the targets, so they are met only if this model meets them.
    for (std::size_t k = 1; k <= alternatives.size() && bestShortfall > 0; ++k) trainAndMeasure(k);
    // A model at the support cap cannot take in what more samples would teach it.
    if (bestShortfall == 0 || update.stopReason == StopReason::SupportCap ||
        learned.size() + fresh.size() > targets.maxTrainingSamples) {
      return result;
    }
    if (counts.accuracy() >= targets.accuracy && level < grownOracles.size()) {
      ++level;  // missing is the TPR alone: learn with more room around the obstacles
      learned.labels = labelsAt(level, learned.points);
    }
    if (level > 0) fresh.labels = labelsAt(level, fresh.points);
    append(learned, fresh);
  }
}

}  // namespace fastron
