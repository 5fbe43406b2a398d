#include "fastron/baselines/fastron_classifier.h"

namespace fastron {

FastronClassifier::FastronClassifier(JointLimits limits, TrainParams params)
    : limits_(std::move(limits)), params_(params), model_(Trainer(limits_, params_).model()) {}

void FastronClassifier::train(const Configurations& q, std::span<const std::int8_t> labels) {
  Trainer trainer(limits_, params_);
  trainer.addPoints(q, labels);
  report_ = trainer.update();
  model_ = trainer.model();
}

}  // namespace fastron
