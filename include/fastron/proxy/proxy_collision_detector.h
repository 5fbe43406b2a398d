#pragma once
// The Fastron pipeline of Fig. 2: label -> update -> active learning, over any exact checker,
// with an optional background thread that keeps the model current while others query it.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <stop_token>
#include <string>
#include <thread>

#include "fastron/core/active_learning.h"
#include "fastron/core/collision_checker.h"
#include "fastron/core/dataset.h"
#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/core/model.h"
#include "fastron/core/trainer.h"
#include "fastron/core/uncertainty_band.h"
#include "fastron/proxy/labelling.h"

namespace FASTRON_API fastron {

struct ProxyParams {
  TrainParams train{};
  ActiveLearningParams activeLearning{};
  std::uint64_t seed = 1;  ///< every random choice of the pipeline derives from it
  /// threads labelling with the oracle (and computing the new points' features and F); 0 = every
  /// hardware thread
  unsigned labelThreads = 0;
  /// Threads of Algorithm 1 in initialize(), step() and learnObservations() (Trainer::update): 1
  /// the calling thread alone, any other value also the process's helper thread when the
  /// training set is large enough to share (Trainer::rowsToShareUpdate()). Background steps run it
  /// on their own thread alone, beside the planner that uses the other cores.
  unsigned trainThreads = 0;
  /// Observations (addObservations) kept for the next step at most; later ones are dropped and
  /// counted, so a caller that outpaces the updates cannot grow memory without bound.
  std::size_t maxPendingObservations = 20000;
  /// Each step() runs Algorithm 1 from zero weights on the relabelled support set and its new
  /// points, instead of from the last weights (the paper's warm start). Under change the last
  /// weights hold the model to the world it learnt before: a support point still free keeps its
  /// negative weight where a box has just come near, and the model calls free what it did not
  /// sample there. Over 2000 updates of the demo's world the warm start's TPR fell to 0.86, while a
  /// model learnt afresh from the same scene reached 0.95 (docs/algorithms.md, "Updates from zero
  /// weights"). defaultProxyParams turns it on for task-space features.
  bool coldStart = false;
  /// Each step() asks the oracle again about the support set, whose labels change when the world
  /// moves. false: a world that stands still (a scene planned in, as `fastron train
  /// --active-learning`, `plan` and `bench motion-bench` train on), where those labels cannot
  /// change: only the new points are labelled, and the model is the same with fewer oracle calls
  /// (on the mesh Panda about half of a 500-point step's labelling).
  bool relabelSupport = true;
  /// Uniform configurations each initialize() / step() labels beside its training points and holds
  /// out of its model to calibrate the model's uncertainty band. Uniform, as a sampling planner's
  /// queries are: a share of the active-learning points, which crowd the support points, left 3.5%
  /// of the colliding configurations below a band calibrated to 0.5% (tests/proxy). Not learned
  /// afterwards: learning them grew the support set by a quarter (bench changing, 7dof-3boxes)
  /// for no clear gain in accuracy. Enough that missRate * colliding ones >= 1 makes the target a
  /// quantile rather than the smallest score. 0 turns calibration off (the band is then the
  /// model's own boundary).
  std::size_t calibrationSamples = 1000;
  /// What the band of each published model is calibrated to.
  BandTargets band{};
  /// Longest the labelling of one initialize() or step() may take (0: no limit). An oracle slower
  /// than that fails the step with an OracleFault soon after the deadline (a checker call already
  /// running is not interrupted), and no model is published.
  std::chrono::nanoseconds labelDeadline{0};
  /// Configurations per labelling whose label is asked twice: two answers fail the step with an
  /// OracleFault (an oracle that contradicts itself cannot be learned). Evenly spaced, not drawn
  /// from the random engine, so they change no result.
  std::size_t repeatedLabels = 8;
  /// After a failed background step, the wait before the next attempt.
  std::chrono::nanoseconds faultRetryPeriod = std::chrono::milliseconds(100);
  /// Each model of point terms only is published with its point field (Model::withPointField,
  /// default options), built on the thread of the update (with the helper thread where Algorithm
  /// 1 shares it): its collision answers then cost grid reads instead of |S| kernel terms. Other
  /// models are published as they are.
  bool pointField = false;
  /// How a published point field answers what its grids leave undecided (FieldAnswers): exactly
  /// by default, or by the grids' estimate alone.
  FieldAnswers fieldAnswers = FieldAnswers::Exact;
};

/// The pipeline tuned for each kind of features: defaultTrainParams(kind, selfCollisionLabels);
/// for task-space features updates from zero weights (coldStart) with 2500 new points each, at
/// most a fifth of them around support points (ActiveLearningParams::exploitationShare) and the
/// rest uniform, which on Baxter among three moving boxes reach accuracy 0.972 and TPR 0.950 at
/// |S| 406 against 0.965, 0.917 and 250 for the paper's update with 500 (`fastron bench
/// changing`, docs/algorithms.md); for joint scaling the paper's update with 500.
ProxyParams defaultProxyParams(FeatureKind kind, bool selfCollisionLabels = false);
/// `params` with the paper's update: Algorithm 1 from the last weights (coldStart false) and
/// Algorithm 2 sampling around every support point first (exploitation share 1); A_max unchanged.
ProxyParams withWarmStart(ProxyParams params);

/// How the background updates are faring (ProxyCollisionDetector::backgroundHealth).
struct BackgroundHealth {
  std::uint64_t steps = 0;              ///< background steps that published a model
  std::uint64_t faults = 0;             ///< background steps that failed (OracleFault)
  std::uint64_t consecutiveFaults = 0;  ///< faults since the last good step: 0 when healthy
  std::string lastFault;                ///< the latest fault's message ("" if none yet)
  std::uint64_t modelVersion = 0;       ///< version of the model being served
};

/// What one initialize() or step() did.
struct StepReport {
  UpdateReport update;
  /// Oracle calls made: support points relabelled, new points, calibration points, and the
  /// repeated calls of ProxyParams::repeatedLabels.
  std::size_t labelled = 0;
  std::size_t added = 0;     ///< new points from sampling or active learning
  std::size_t observed = 0;  ///< labelled configurations from addObservations learned in this step
  std::chrono::nanoseconds sampleTime{0}, labelTime{0}, total{0};
  std::uint64_t modelVersion = 0;  ///< 1 after initialize(), +1 per step()
  BandCalibration calibration;     ///< the new model's band (calibrationSamples held-out points)
};

/// A published model with the uncertainty band calibrated for it (e.g. for a HybridChecker).
struct CalibratedModel {
  std::shared_ptr<const Model> model;
  BandCalibration calibration;
  std::uint64_t version = 0;  ///< 1 for initialize()'s model, +1 per model published after it
};

class ProxyCollisionDetector {
 public:
  /// `oracle` labels configurations (it must be safe to call from several threads unless
  /// params.labelThreads == 1) and its dof() must equal features.configurationDim(). The models
  /// learn on `features` (e.g. a robot's task-space features, see geometry/robot_features.h).
  ProxyCollisionDetector(std::shared_ptr<const CollisionChecker> oracle, FeatureMap features,
                         ProxyParams params = {});
  /// Joint-space features: the joint values scaled by `limits` (the paper's input).
  ProxyCollisionDetector(std::shared_ptr<const CollisionChecker> oracle, JointLimits limits,
                         ProxyParams params = {});
  ~ProxyCollisionDetector();
  ProxyCollisionDetector(const ProxyCollisionDetector&) = delete;
  ProxyCollisionDetector& operator=(const ProxyCollisionDetector&) = delete;

  /// n uniform samples within the joint limits, labelled, then Algorithm 1.
  StepReport initialize(std::size_t n);
  /// Algorithm 1 on configurations the caller has labelled already (e.g. one labelling shared by
  /// models on other features): no oracle call, no calibration (the band is the model's own
  /// boundary until a step calibrates one). Throws InvalidArgument on an empty set, a wrong
  /// column count, a non-finite value or a label other than +1 / -1.
  StepReport initialize(const Dataset& labelled);

  /// One cycle for a changed environment: Algorithm 2 on the current support set, relabel the
  /// support set, label the new points, Algorithm 1. Throws Error before initialize(), and
  /// OracleFault when the oracle fails (ProxyParams::labelDeadline, repeatedLabels): the
  /// detector is then as it was before the call, serving the same model.
  StepReport step();

  /// Exact answers the caller already has (e.g. VerifiedPlan::exactAnswers from verifying and
  /// repairing a plan on this model): the next step() learns them with its own points, without
  /// asking the oracle again, so the model stops repeating a miss where the planner went. Safe
  /// to call from any thread, also while the background thread runs. In a changing world the
  /// labels are as old as the answers; the support points among them are relabelled at the step
  /// after. Measured in `fastron demo` (boxes move every tick): all ~300 answers of each plan
  /// made the model worse (accuracy 0.874 +- 0.173 against 0.965, 20% of plans repaired against
  /// 8%: dense, stale points); only the answers the model got wrong (answersMissedBy) left it as
  /// good and changed nothing measurable, so feed those. Throws InvalidArgument on a wrong column
  /// count, a non-finite value or a label other than +1 / -1; beyond params.maxPendingObservations
  /// waiting answers the rest are dropped (droppedObservations()).
  void addObservations(const Dataset& answers);
  /// Learns the waiting observations (addObservations) now, without asking the oracle anything:
  /// no relabelling and no active learning, for a world that has not moved since the last step
  /// (a static scene between planning queries). The band stays the last calibrated one. Returns
  /// the update's report (observed = 0 and no new model when nothing was waiting). Throws Error
  /// before initialize().
  StepReport learnObservations();
  std::size_t droppedObservations() const;

  /// The latest published model. A model, once returned, never changes, so callers keep querying
  /// it without any lock while newer ones are built. Fetching it holds a mutex only for the copy
  /// of a shared_ptr. Throws Error before initialize().
  std::shared_ptr<const Model> model() const;
  /// The latest published model together with its band (one consistent pair). Throws Error before
  /// initialize().
  CalibratedModel calibratedModel() const;

  /// Runs step() in a loop on a background thread, publishing each new model atomically.
  /// `onStep` (optional) is called on that thread after each step. Steps start at most once per
  /// `minPeriod` (default: back to back). Give the period at which the world changes (e.g. the
  /// sensing rate): each step on an unchanged world only adds active-learning points near the
  /// boundary, so the support set, and with it the query time, keeps growing.
  /// A step the oracle fails (OracleFault) is a fault, not the end: the last good model stays
  /// published, backgroundHealth() reports it, and the loop tries again after
  /// params.faultRetryPeriod until the oracle recovers.
  void startBackground(std::function<void(const StepReport&)> onStep = {},
                       std::chrono::nanoseconds minPeriod = {});
  /// Stops and joins the background thread, interrupting a step between two oracle calls;
  /// rethrows any other exception that ended its loop (e.g. one `onStep` threw).
  void stopBackground();
  bool backgroundRunning() const { return worker_.joinable(); }
  /// Steps and faults of the background thread since startBackground().
  BackgroundHealth backgroundHealth() const;

  /// Shared, e.g. with a HybridChecker that asks what the model was taught.
  const std::shared_ptr<const CollisionChecker>& oracle() const { return oracle_; }
  const FeatureMap& features() const { return features_; }
  const JointLimits& limits() const { return features_.limits(); }
  const ProxyParams& params() const { return params_; }

 private:
  /// step(), interrupted between oracle calls when `stop` is requested (LabellingStopped), with
  /// Algorithm 1 on `trainThreads` (Trainer::update).
  StepReport runStep(const std::stop_token& stop, unsigned trainThreads);
  /// The labelling guard of a step that starts now.
  LabelGuard labelGuard(const std::stop_token& stop) const;
  /// Adds the waiting observations to the trainer (stepMutex_ held); returns how many. They keep
  /// waiting until dropLearnedObservations: a step that fails after this leaves them to the next.
  std::size_t learnPendingObservations();
  /// Runs Trainer::addPoints' chunks on params_.labelThreads threads (forEachChunk).
  ChunkRunner onLabelThreads() const;
  /// Forgets the first `count` waiting observations (learned by a step that succeeded).
  void dropLearnedObservations(std::size_t count);
  /// Builds the trained model (with its point field when params_.pointField asks, on `threads`:
  /// PointFieldOptions::threads), calibrates its band on the held-out points and publishes both.
  StepReport finish(StepReport report, std::chrono::steady_clock::time_point start,
                    const Configurations& heldOut, const Labels& heldOutLabels, unsigned threads);

  std::shared_ptr<const CollisionChecker> oracle_;
  FeatureMap features_;
  ProxyParams params_;
  Rng rng_;
  Trainer trainer_;
  std::mutex stepMutex_;  // one initialize()/step() at a time
  std::uint64_t version_ = 0;
  // Not std::atomic<std::shared_ptr>: libstdc++ 12 unlocks its load with relaxed order, a data
  // race that ThreadSanitizer reports. A mutex around the pointer copy is as cheap, and correct.
  mutable std::mutex modelMutex_;
  CalibratedModel published_;        // the latest model and its band
  mutable std::mutex pendingMutex_;  // for the three below only
  std::vector<double> pendingValues_;
  Labels pendingLabels_;
  std::size_t dropped_ = 0;
  std::mutex pauseMutex_;              // for pause_ only
  std::condition_variable_any pause_;  // wakes the worker between steps when stopping
  std::jthread worker_;
  std::exception_ptr workerError_;
  mutable std::mutex healthMutex_;  // for health_ only
  BackgroundHealth health_;
};

/// A model of a scene that stands still, as `fastron plan` and the planning experiments train
/// one: initialize(samples), then `updates` active-learning steps. Returns the last report, its
/// `total` the time of them all.
StepReport trainStatic(ProxyCollisionDetector& proxy, std::size_t samples, std::size_t updates);

/// The rows of `answers` whose label `model` gets wrong: where it would have misled a planner.
/// Throws InvalidArgument when the column count is not the model's dimension.
Dataset answersMissedBy(const Model& model, const Dataset& answers);

}  // namespace fastron
