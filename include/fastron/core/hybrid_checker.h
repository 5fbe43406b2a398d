#pragma once
// A collision checker that answers from a Fastron model where its score is clearly on one side of
// the boundary and asks the exact checker inside the model's uncertainty band.

#include <atomic>
#include <cstdint>
#include <memory>

#include "fastron/core/collision_checker.h"
#include "fastron/core/export.h"
#include "fastron/core/model.h"
#include "fastron/core/uncertainty_band.h"

namespace FASTRON_API fastron {

/// Model where sure, exact checker in the band (see uncertainty_band.h for the calibration).
/// Never answers "free" from the model for a score inside the band. A CollisionChecker, so it is
/// a planner's validity checker and motion validator (CollisionSource) and labels like any
/// oracle; a run of configurations (an edge) is scored as one batch on the model's vectorised
/// path and only the ones in the band go to the exact checker. Safe to call from many threads
/// when `exact` is.
class HybridChecker final : public CollisionChecker {
 public:
  /// Throws InvalidArgument on a null model or checker, different dof, or a band with
  /// lower > 0 or upper < 0.
  HybridChecker(std::shared_ptr<const Model> model, std::shared_ptr<const CollisionChecker> exact,
                UncertaintyBand band);

  /// "Fastron+<exact name>".
  std::string name() const override;
  std::size_t dof() const override { return model_->dim(); }
  bool answersFromAModel() const override { return true; }

  const Model& model() const { return *model_; }
  const UncertaintyBand& band() const { return band_; }
  /// Configurations answered by the model, and by the exact checker, since construction.
  std::uint64_t modelAnswers() const { return modelAnswers_.load(std::memory_order_relaxed); }
  std::uint64_t exactAnswers() const { return exactAnswers_.load(std::memory_order_relaxed); }
  /// exactAnswers / (modelAnswers + exactAnswers); 0 before any query.
  double exactShare() const;

 protected:
  bool check(const double* q) const override;
  std::size_t checkFirst(const double* q, std::size_t n) const override;

 private:
  /// The answer for a configuration with model score s.
  bool decide(const double* q, double s) const;

  std::shared_ptr<const Model> model_;
  std::shared_ptr<const CollisionChecker> exact_;
  UncertaintyBand band_;
  mutable std::atomic<std::uint64_t> modelAnswers_{0}, exactAnswers_{0};
};

}  // namespace fastron
