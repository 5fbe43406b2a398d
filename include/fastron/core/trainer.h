#pragma once
// Algorithm 1 of the paper: Fastron model updating.

#include <Eigen/Core>
#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/core/kernel.h"
#include "fastron/core/model.h"
#include "fastron/core/simd.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

struct TrainParams {
  Kernel kernel{};                      ///< kernel and gamma used for the Gram matrix
  double beta = 1;                      ///< conditional bias, >= 1 (paper, Sec. II-D)
  std::size_t maxIterations = 5000;     ///< iter_max of Algorithm 1, per update
  std::size_t maxSupportPoints = 3000;  ///< S_max, the support-point cap
  /// A weight may grow to at most this many times beta (infinity: no limit, as in the paper).
  /// Two points with nearly the same features and opposite labels need weights that grow as
  /// 1 / (1 - k(x_a, x_b)) for both margins to be positive, and warm-started updates add to them
  /// update after update: on the demo's world with 2500 new points per update they passed 1e30
  /// (where float queries mean nothing, long before) at update 369. Converging weights reach
  /// 2e4 beta in a smooth planar world (tests/proxy, gamma 3 over 2 m); at 1000 beta that test's
  /// training stopped early and lost accuracy in 5 and 7 of two batches of 600 runs beside two
  /// busy loops, none of 1200 at 1e5 (docs/algorithms.md).
  double maxWeightOverBeta = 1e5;
  /// Algorithm 1's Gram columns in float for a rational-quadratic kernel (a Gaussian's stay
  /// double): training 1.3-1.9 times faster at 7 to 27 features (docs/performance.md). F then
  /// differs from K alpha by at most Trainer::hypothesisErrorBound(), and before an update
  /// stops, every margin whose sign that bound leaves open is computed again exactly, so Claim 1,
  /// the misclassified count and the revert safeguard stay exact (trainer.cpp). false: double
  /// columns, the iterations, support set and weights of the scalar reference
  /// (reference_trainer.h).
  bool floatGramColumns = true;
};

/// Throws InvalidArgument naming the field that is out of range.
void validate(const TrainParams& params);

/// The rational-quadratic kernel and the conditional bias beta that suit each kind of features on
/// a 7-joint arm, chosen by the sweeps in docs/algorithms.md: joint scaling gamma 5, beta 500
/// (the paper's 7-DOF settings, Sec. IV-B); task-space features (metres) a term per control point
/// beside the whole vector's (share 0.5), gamma 40, beta 30. A task-space model whose labels
/// include the robot's collisions with itself (`selfCollisionLabels`) gets one term, gamma 40,
/// beta 10: a self-collision is a relation between two links, which terms of single points do not
/// describe (a mesh Panda model of obstacles and self-collisions needed as many support points
/// with point terms, each costing 1.7 times as much to query).
TrainParams defaultTrainParams(FeatureKind kind, bool selfCollisionLabels = false);

/// The support-point cap of a robot's models (the CLI with --robot, sceneTrainParams, the
/// experiments): a 7-joint arm in clutter needs more than the paper's 3000.
inline constexpr std::size_t kRobotSupportCap = 5000;
/// Uniform samples for a scene that stands still, learned at once (sceneTrainParams).
inline constexpr std::size_t kSceneSamples = 16000;
/// For the most accurate model of a scene that stands still, learned at once from kSceneSamples
/// uniform samples and held-out rounds (`fastron train --scene`, trainToHeldOutTargets):
/// defaultTrainParams with an iteration limit of 20000 and a cap of 5000 support points, and for
/// task-space features without self-collision labels point terms alone (no whole-vector term),
/// gamma 60 and beta 40: with control points along the links' geometry
/// (pipeline::heldOutControlPoints) such a model is as accurate as one with the whole term, and
/// its point field answers 3.7-12x faster than FK+FCL where the whole term's sum answered
/// 0.5-5.8x (docs/performance.md, "Answers from tabulated point terms"). Uniform samples of a scene
/// are 1-9% colliding, and the colliding class needs a larger bias than updates under change (whose
/// Algorithm 2 samples lie near the boundary); the narrower kernel finds more of the thin colliding
/// regions (shelves) once the rounds have supplied the samples it needs. The mesh Panda in the 20
/// sample MotionBenchMaker scenes, 3 seeds, with the rounds: accuracy 0.976 and TPR 0.962, both
/// 0.97 and 0.95 in 49 of 60 trainings, against 44 with gamma 40 and beta 60 and 34 without rounds
/// (docs/log/2026-11-24-training-on-scenes-rounds-and-candidates.md, "Training on one scene").
/// Planners that train per query (`fastron plan`, motion-bench) keep the smaller, cheaper models:
/// there larger ones planned slower, counting their training or not.
TrainParams sceneTrainParams(FeatureKind kind, bool selfCollisionLabels = false);

enum class StopReason {
  Converged,       ///< every training point has positive margin and no support point is redundant
  SupportCap,      ///< a misclassified point needed a new support point, the cap was reached and
                   ///< no redundant support point could be removed
  IterationLimit,  ///< iter_max iterations were used
  WeightLimit,     ///< a misclassified point needed a weight beyond maxWeightOverBeta beta and
                   ///< no redundant support point could be removed
};
std::string_view toString(StopReason reason);

/// What one call of Trainer::update did.
struct UpdateReport {
  std::size_t iterations = 0;  ///< weight updates plus redundant-point removals
  StopReason stopReason = StopReason::Converged;
  std::size_t trainingPoints = 0;  ///< N before non-support points were discarded
  std::size_t misclassified = 0;   ///< training points with margin <= 0 at the end
  std::size_t supportCount = 0;    ///< |S| after the update
  /// Gram columns evaluated by this update: one per weight change (columns are computed when
  /// needed, not cached: see trainer.cpp)
  std::size_t gramColumnsComputed = 0;
  bool reverted = false;  ///< the revert safeguard restored the earlier solution
  std::size_t misclassifiedBeforeRevert = 0;  ///< count that made the safeguard revert
  /// Iterations whose rows a second core shared (Trainer::update(threads)); 0 on one core
  std::size_t sharedIterations = 0;
  std::chrono::nanoseconds elapsed{0};
};

/// Calls body(begin, end) once for each chunk [0, chunk), [chunk, 2 chunk), ... of [0, n), in
/// any order and on any threads (e.g. proxy's forEachChunk); bodies write to disjoint memory and
/// do not throw unless their input is invalid, and the first exception is rethrown to the caller.
using ChunkRunner = std::function<void(std::size_t n, std::size_t chunk,
                                       const std::function<void(std::size_t, std::size_t)>& body)>;

/// Owns the training set (each configuration beside its features X), labels y, weights alpha,
/// hypothesis F = K alpha and the lazily evaluated Gram matrix. Between updates only support points
/// are kept, so memory is O(N |S|) during an update and O(|S|^2) after it; a dense N x N matrix is
/// never allocated.
class Trainer {
 public:
  /// Algorithm 1 runs on the features `features` maps configurations to.
  Trainer(FeatureMap features, TrainParams params);
  /// Joint-space features: the joint values scaled by `limits` (the paper's input).
  Trainer(JointLimits limits, TrainParams params)
      : Trainer(FeatureMap::jointScaling(std::move(limits)), params) {}

  /// Appends configurations (joint values, one per row) with labels +1 / -1, keeping each
  /// configuration beside its features (nothing converts back). Their weights start
  /// at 0 and their F is computed from the current weights: the kernel between each support
  /// point and the new rows (paper, "Dynamic Data Structures"). The features and F of the new
  /// rows are computed in chunks given to `run` (e.g. spread over the cores); by default on the
  /// calling thread. Nothing changes if a configuration is invalid (InvalidArgument).
  void addPoints(const Configurations& q, std::span<const std::int8_t> labels,
                 const ChunkRunner& run = {});

  /// Replaces the labels of the current points (same order as `configurations()`), e.g. after the
  /// obstacles moved. A support point whose weight sign disagrees with its new label gets weight
  /// 0, and F is corrected.
  void relabel(std::span<const std::int8_t> labels);

  /// Sets every weight (and so F) to 0, keeping the points: the next update() runs Algorithm 1
  /// from scratch on them instead of from the last weights.
  void forgetWeights();

  /// Algorithm 1: greedy most-negative-margin updates with conditional bias, support-point cap,
  /// redundant support point removal once all margins are positive, the revert safeguard, and
  /// finally removal of the non-support points. Never prints. `threads` 1 runs it on the calling
  /// thread; any other value (0: every core), with at least rowsToShareUpdate() training points,
  /// also on the process's helper thread, which takes half of every iteration's rows and spins
  /// between iterations (one such update at a time in a process: the others, and the rest of an
  /// update whose helper was preempted, run on the calling thread). The result is the same bit
  /// for bit.
  UpdateReport update(unsigned threads = 1);

  /// Training points from which update(threads != 1) shares its iterations with a second core
  /// when Algorithm 1 runs on `path`: a row costs twice as much on AVX2 as on AVX-512, so sharing
  /// pays from half as many rows. `BM_TrainOnThreads` (12 features with point terms), AVX-512
  /// (2026-11-26): 1500 points 0.35 ms on one core against 0.45 ms on two, 3000 1.42 against
  /// 1.37 ms, 8000 8.9 against 5.8 ms; AVX2 (AMD Zen 3, 2026-11-28): 1500 points 0.54-0.63
  /// against 0.50-0.59 ms, 3000 2.4-3.0 against 1.8-2.1 ms.
  static std::size_t rowsToShareUpdate(SimdPath path = activeSimdPath());

  /// Snapshot of the current support set (points with nonzero weight).
  std::shared_ptr<const Model> model() const;

  /// Joint values per configuration.
  std::size_t dim() const { return features_.configurationDim(); }
  std::size_t size() const { return static_cast<std::size_t>(y_.size()); }
  std::size_t supportCount() const { return supportCount_; }
  const FeatureMap& features() const { return features_; }
  const JointLimits& limits() const { return features_.limits(); }
  const TrainParams& params() const { return params_; }
  /// Training configurations (joint values), one per row.
  const Configurations& configurations() const { return q_; }
  /// Their features, one per row.
  const Eigen::MatrixXd& points() const { return x_; }
  const Eigen::VectorXd& labels() const { return y_; }
  const Eigen::VectorXd& weights() const { return alpha_; }
  /// The hypothesis F = K alpha at every training point, maintained incrementally: within
  /// hypothesisErrorBound() of K alpha computed exactly, its signs exact after update().
  const Eigen::VectorXd& hypothesis() const { return f_; }
  /// A bound on |F - K alpha| at every training point: the float columns' error (0 with double
  /// columns) times the weight changes since F was last computed exactly.
  double hypothesisErrorBound() const { return fError_; }

 private:
  /// The Gram column of point i, K(x_i, x_j) for every training point j, into column_.
  void computeColumn(Eigen::Index i);
  Eigen::Map<const Eigen::VectorXd> column() const {
    return {column_.data(), static_cast<Eigen::Index>(column_.size())};
  }
  std::size_t countMisclassified(const Eigen::VectorXd& f) const;
  /// Computes again exactly F of the weights `alpha` at every row whose sign an error of `bound`
  /// could change (all rows when they are many): afterwards every sign of f is exact. Returns true
  /// when every row was recomputed (f is then exact).
  bool settleSigns(Eigen::VectorXd& f, const Eigen::VectorXd& alpha, double bound) const;
  void removeNonSupportPoints();

  FeatureMap features_;
  TrainParams params_;
  Configurations q_;    // N x dim(), joint values
  Eigen::MatrixXd x_;   // N x featureDim(), features of q_ rounded to float
  Eigen::MatrixXf xf_;  // the same, as floats: what the Gram columns read (trainer.cpp)
  Eigen::VectorXd y_;   // +1 / -1
  Eigen::VectorXd alpha_;
  Eigen::VectorXd f_;
  std::size_t supportCount_ = 0;
  std::vector<double> column_;       // the last Gram column computed, of length N (no allocation
                                     // per iteration; columns are computed, not cached)
  std::size_t columnsComputed_ = 0;  // during the current update
  double columnError_ = 0;           // bound on a Gram column value's error: 0 for double columns
  double fError_ = 0;                // hypothesisErrorBound()
};

}  // namespace fastron
