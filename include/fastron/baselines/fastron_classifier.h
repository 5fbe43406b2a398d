#pragma once
// Fastron (Algorithm 1 on a fixed dataset) behind the Classifier interface.

#include "fastron/baselines/classifier.h"
#include "fastron/core/export.h"
#include "fastron/core/trainer.h"

namespace FASTRON_API fastron {

class FastronClassifier final : public Classifier {
 public:
  FastronClassifier(JointLimits limits, TrainParams params);
  std::string name() const override { return "Fastron"; }
  void train(const Configurations& q, std::span<const std::int8_t> labels) override;
  double score(const double* q) const override { return model_->score(q); }
  std::size_t supportCount() const override { return model_->supportCount(); }
  const UpdateReport& report() const { return report_; }
  const std::shared_ptr<const Model>& model() const { return model_; }

 private:
  JointLimits limits_;
  TrainParams params_;
  std::shared_ptr<const Model> model_;
  UpdateReport report_;
};

}  // namespace fastron
