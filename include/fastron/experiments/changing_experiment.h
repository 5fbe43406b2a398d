#pragma once
// The paper's changing-environment experiments (Sec. IV-B): Baxter's right arm with 4, 6 or 7
// actuated joints and one 0.2 m box on a random walk, and 7 joints with three boxes. Fastron
// learns from FCL labels and from GJK labels and is checked against FCL at every update, beside
// FK + GJK and FK + FCL (Figs. 9 and 11 and the tables of Figs. 8 and 10); and the obstacle
// sweep: query times against 1 to 100 obstacles and the share of C-space in collision (Fig. 12).

#include <optional>
#include <string>
#include <vector>

#include "fastron/core/feature_map.h"
#include "fastron/experiments/progress.h"
#include "fastron/experiments/table.h"

namespace fastron::experiments {

struct ChangingOptions {
  std::size_t trials = 3;
  std::size_t steps = 50;  ///< obstacle moves (model updates) per trial
  std::uint64_t seed = 1;
  bool quick = false;
  /// Fastron's input. With task-space features a joint-space Fastron (FCL) runs beside them, so
  /// the paper's row stays in the table.
  FeatureKind features = FeatureKind::Kinematic;
  /// Settings of the Fastron models on options.features (not of the joint-space row beside
  /// them), for tuning; 0 keeps the default: the case's gamma and beta for joints,
  /// defaultTrainParams for task space, defaultVariance for the active-learning spread.
  double gamma = 0, beta = 0, variance = 0;
  /// A_max of the models on options.features; 0 keeps the default (defaultProxyParams: 2500 for
  /// task space, 500 for joints, the paper's).
  std::size_t activeSamples = 0;
  /// The models on options.features update as in the paper (from their last weights, Algorithm 2
  /// sampling around every support point) even with task-space features, whose default is from
  /// zero weights with most samples uniform (ProxyParams::coldStart).
  bool warmStart = false;
  /// When > 0, a row "Fastron (FCL, pruned)": the Fastron (FCL) model of each update reduced by
  /// pruneSupport on this many fresh uniform configurations (support_reduction.h).
  std::size_t pruneSamples = 0;
  /// When > 0, a row "Fastron (FCL, merged)": the same model reduced by mergeSupport(radius).
  double mergeRadius = 0;
  /// The kernel's point terms (Kernel::block, wholeShare) of the models on options.features;
  /// unset keeps defaultTrainParams'.
  std::optional<std::uint32_t> kernelBlock;
  std::optional<double> wholeShare;
  std::vector<std::string> cases{"4dof", "6dof", "7dof", "7dof-3boxes"};
};

/// One row per (case, trial, step, method): accuracy, tpr, tnr against FCL, support, query_s,
/// update_s (labelling + training). Methods: "Fastron (FCL)", "Fastron (GJK)" on
/// options.features, "Fastron (FCL, joints)" when those are task-space, the pruned and merged
/// rows when asked for, "FK+GJK", "FK+FCL". Their update_s includes the reduction.
Table runChanging(const ChangingOptions& options, const Progress& progress);
std::string changingReport(const Table& results, const ChangingOptions& options);

struct SweepOptions {
  std::size_t trials = 3;
  std::uint64_t seed = 1;
  bool quick = false;
  FeatureKind features = FeatureKind::Kinematic;
  std::vector<std::size_t> obstacles{1, 2, 5, 10, 20, 50, 100};
};

/// One row per (obstacles, trial, method): query_s, support, cobs_fraction.
Table runObstacleSweep(const SweepOptions& options, const Progress& progress);
std::string sweepReport(const Table& results, const SweepOptions& options);

}  // namespace fastron::experiments
