#include "fastron/proxy/held_out_training.h"

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

bool meets(const ConfusionCounts& counts, const HeldOutTargets& targets) {
  // A scene without colliding configurations has no TPR to miss.
  const bool tprMet =
      counts.truePositives + counts.falseNegatives == 0 || counts.tpr() >= targets.truePositiveRate;
  return counts.accuracy() >= targets.accuracy && tprMet;
}

}  // namespace

HeldOutTraining trainToHeldOutTargets(const CollisionChecker& oracle, const FeatureMap& features,
                                      const TrainParams& params, std::size_t initialSamples,
                                      const HeldOutTargets& targets, Rng& rng, unsigned threads) {
  validate(targets);
  if (initialSamples == 0) throw InvalidArgument("initial samples must be at least 1");
  const auto labelled = [&](std::size_t n) {
    Dataset data;
    data.points = uniformConfigurations(features.limits(), n, rng);
    data.labels = labelConfigurations(oracle, data.points, threads);
    return data;
  };
  const Dataset initial = labelled(initialSamples);
  Configurations learned = initial.points;
  Labels labels = initial.labels;

  HeldOutTraining result;
  for (;;) {
    Trainer trainer(features, params);
    trainer.addPoints(learned, labels);
    result.lastUpdate = trainer.update();
    result.model = trainer.model();
    result.trainingSamples = labels.size();

    const Dataset fresh = labelled(targets.samplesPerRound);
    const ConfusionCounts counts = evaluate(*result.model, fresh.points, fresh.labels);
    result.rounds.push_back({labels.size(), result.model->supportCount(), counts});
    if (meets(counts, targets) || labels.size() + fresh.size() > targets.maxTrainingSamples) {
      return result;
    }
    learned.conservativeResize(learned.rows() + fresh.points.rows(), Eigen::NoChange);
    learned.bottomRows(fresh.points.rows()) = fresh.points;
    labels.insert(labels.end(), fresh.labels.begin(), fresh.labels.end());
  }
}

}  // namespace fastron
