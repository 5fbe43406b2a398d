#include "fastron/proxy/proxy_collision_detector.h"

#include <algorithm>
#include <future>
#include <string>
#include <utility>

#include "fastron/core/error.h"
#include "fastron/core/parallel_chunks.h"
#include "fastron/proxy/labelling.h"

namespace fastron {

using Clock = std::chrono::steady_clock;

namespace {

/// Throws InvalidArgument, naming `what` ("observation"), unless `data` has `dim` columns, a row
/// per label, finite values and labels +1 / -1.
void checkLabelled(const Dataset& data, std::size_t dim, const std::string& what) {
  if (data.dim() != dim || static_cast<std::size_t>(data.points.rows()) != data.size()) {
    throw InvalidArgument(what + "s have " + std::to_string(data.dim()) + " columns and " +
                          std::to_string(data.points.rows()) + " rows for " +
                          std::to_string(data.size()) + " labels; the model has " +
                          std::to_string(dim) + " joints");
  }
  if (!data.points.allFinite()) {
    throw InvalidArgument(what + "s must be finite (found NaN or inf)");
  }
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (data.labels[i] != 1 && data.labels[i] != -1) {
      throw InvalidArgument(what + " " + std::to_string(i) + " has label " +
                            std::to_string(data.labels[i]) + ", expected +1 or -1");
    }
  }
}

}  // namespace

ProxyCollisionDetector::ProxyCollisionDetector(std::shared_ptr<const CollisionChecker> oracle,
                                               FeatureMap features, ProxyParams params)
    : oracle_(std::move(oracle)),
      features_(std::move(features)),
      params_(params),
      rng_(params.seed),
      trainer_(features_, params.train) {
  if (!oracle_) throw InvalidArgument("ProxyCollisionDetector: no oracle given");
  if (oracle_->dof() != features_.configurationDim()) {
    throw InvalidArgument("ProxyCollisionDetector: oracle '" + oracle_->name() + "' has " +
                          std::to_string(oracle_->dof()) + " dof but the joint limits have " +
                          std::to_string(features_.configurationDim()));
  }
  validate(params_.activeLearning);
  validate(params_.band);
}

ProxyCollisionDetector::ProxyCollisionDetector(std::shared_ptr<const CollisionChecker> oracle,
                                               JointLimits limits, ProxyParams params)
    : ProxyCollisionDetector(std::move(oracle), FeatureMap::jointScaling(std::move(limits)),
                             params) {}

ProxyCollisionDetector::~ProxyCollisionDetector() {
  worker_.request_stop();
  if (worker_.joinable()) worker_.join();
}

StepReport ProxyCollisionDetector::finish(StepReport report, Clock::time_point start,
                                          const Configurations& heldOut,
                                          const Labels& heldOutLabels, unsigned threads) {
  std::shared_ptr<const Model> next = trainer_.model();  // built outside the lock
  if (params_.pointField && next->hasOnlyPointTerms()) {
    PointFieldOptions field;
    field.threads = threads;
    // Fine blocks would cost each update's build more: on the demo's models (|S| about 330) they
    // added 40 ms to an 80 ms build and answered no faster.
    field.refinement = 1;
    field.answers = params_.fieldAnswers;
    next = next->withPointField(field);
  }
  if (!heldOutLabels.empty()) {
    report.calibration = calibrateBand(next->scoreBatch(heldOut), heldOutLabels, params_.band);
  }
  {
    const std::lock_guard lock(modelMutex_);
    published_.model.swap(next);
    published_.calibration = report.calibration;
    published_.version = ++version_;
  }  // the previous model is released here, outside the lock, if no reader holds it
  report.modelVersion = version_;
  report.total = Clock::now() - start;
  return report;
}

StepReport ProxyCollisionDetector::initialize(std::size_t n) {
  const std::lock_guard lock(stepMutex_);
  const auto start = Clock::now();
  StepReport report;
  const std::size_t calibration = params_.calibrationSamples;
  const Configurations q = uniformConfigurations(limits(), n + calibration, rng_);
  const auto labelStart = Clock::now();
  report.sampleTime = labelStart - start;
  const Labels labels = labelConfigurations(*oracle_, q, params_.labelThreads, labelGuard({}));
  report.labelTime = Clock::now() - labelStart;
  report.labelled = n + calibration + std::min(params_.repeatedLabels, n + calibration);
  report.added = n;
  trainer_ = Trainer(features_, params_.train);
  const auto learned = static_cast<Eigen::Index>(n);
  trainer_.addPoints(q.topRows(learned), {labels.data(), n}, onLabelThreads());
  report.update = trainer_.update(params_.trainThreads);
  return finish(report, start, q.bottomRows(static_cast<Eigen::Index>(calibration)),
                Labels(labels.begin() + learned, labels.end()), params_.trainThreads);
}

StepReport ProxyCollisionDetector::initialize(const Dataset& labelled) {
  if (labelled.size() == 0) {
    throw InvalidArgument("initialize: no labelled configurations to learn");
  }
  checkLabelled(labelled, features_.configurationDim(), "labelled configuration");
  const auto dim = static_cast<Eigen::Index>(features_.configurationDim());
  const std::lock_guard lock(stepMutex_);
  const auto start = Clock::now();
  StepReport report;
  report.added = labelled.size();
  trainer_ = Trainer(features_, params_.train);
  trainer_.addPoints(labelled.points, labelled.labels, onLabelThreads());
  report.update = trainer_.update(params_.trainThreads);
  return finish(report, start, Configurations(0, dim), {}, params_.trainThreads);
}

LabelGuard ProxyCollisionDetector::labelGuard(const std::stop_token& stop) const {
  return {.deadline = params_.labelDeadline.count() > 0 ? Clock::now() + params_.labelDeadline
                                                        : Clock::time_point::max(),
          .repeatedRows = params_.repeatedLabels,
          .stop = stop};
}

StepReport ProxyCollisionDetector::step() {
  return runStep(std::stop_token{}, params_.trainThreads);
}

StepReport ProxyCollisionDetector::runStep(const std::stop_token& stop, unsigned trainThreads) {
  const std::lock_guard lock(stepMutex_);
  if (version_ == 0) throw Error("ProxyCollisionDetector::step() called before initialize()");
  const auto start = Clock::now();
  StepReport report;

  // The published model is the trainer's current support set: nothing changes the trainer between
  // steps (stepMutex_), so Algorithm 2 samples around it instead of building the same model again.
  const Configurations fresh = activeLearning(*model(), params_.activeLearning, rng_);
  const Configurations calibration =
      uniformConfigurations(limits(), params_.calibrationSamples, rng_);
  const auto support = static_cast<Eigen::Index>(trainer_.size());
  // The support set is labelled again unless the world stands still (relabelSupport).
  const Eigen::Index relabelled = params_.relabelSupport ? support : 0;
  Configurations learnt(relabelled + fresh.rows(),
                        static_cast<Eigen::Index>(features_.configurationDim()));
  learnt.topRows(relabelled) = trainer_.configurations().topRows(relabelled);
  learnt.bottomRows(fresh.rows()) = fresh;
  const auto labelStart = Clock::now();
  report.sampleTime = labelStart - start;

  // The uniform points held out to calibrate the new model's band do not depend on it: they are
  // labelled while the support set and the active-learning points are, and, when Algorithm 1
  // runs on one core (a background step, or too few points to share), while it runs. An oracle
  // that may only be called from one thread (labelThreads 1) labels them where they are awaited.
  // (A future of std::async waits for its task when destroyed: if anything below throws, the
  // labelling is over before the step returns. Without calibration points no thread is started.)
  const auto policy = params_.labelThreads == 1 || calibration.rows() == 0 ? std::launch::deferred
                                                                           : std::launch::async;
  // Their labels never enter the model: the repeated rows that test the oracle are asked among
  // the labels that do.
  LabelGuard heldOutGuard = labelGuard(stop);
  heldOutGuard.repeatedRows = 0;
  auto heldOut = std::async(policy, [&] {
    return labelConfigurations(*oracle_, calibration, params_.labelThreads, heldOutGuard);
  });
  const Labels labels =
      labelConfigurations(*oracle_, learnt, params_.labelThreads, labelGuard(stop));
  report.labelTime = Clock::now() - labelStart;
  report.labelled = labels.size() + static_cast<std::size_t>(calibration.rows()) +
                    std::min(params_.repeatedLabels, labels.size());
  report.added = static_cast<std::size_t>(fresh.rows());

  Trainer before = trainer_;  // restored when the held-out labelling fails
  Labels heldOutLabels;
  const auto awaitHeldOut = [&] {
    const auto waitStart = Clock::now();
    try {
      heldOutLabels = heldOut.get();
    } catch (...) {
      trainer_ = std::move(before);  // a step the oracle fails leaves the detector as it was,
      throw;                         // its observations still waiting
    }
    report.labelTime += Clock::now() - waitStart;  // the labelling Algorithm 1 did not hide
  };
  // Forgotten first, so that relabel has no weight to correct (a Gram column per flipped point).
  if (params_.coldStart) trainer_.forgetWeights();
  if (relabelled > 0) trainer_.relabel({labels.data(), static_cast<std::size_t>(relabelled)});
  trainer_.addPoints(fresh, Labels(labels.begin() + relabelled, labels.end()), onLabelThreads());
  report.observed = learnPendingObservations();
  // Algorithm 1 on two cores needs the other core: then the held-out labelling ends first.
  const bool trainOnTwoCores = trainThreads != 1 && trainer_.size() >= Trainer::rowsToShareUpdate();
  if (trainOnTwoCores) awaitHeldOut();
  report.update = trainer_.update(trainOnTwoCores ? trainThreads : 1);
  if (!trainOnTwoCores) awaitHeldOut();
  dropLearnedObservations(report.observed);
  return finish(report, start, calibration, heldOutLabels, trainOnTwoCores ? trainThreads : 1);
}

ChunkRunner ProxyCollisionDetector::onLabelThreads() const {
  // The new points' features and F, spread like the labelling (2000 points, |S| 540, 12
  // features: 0.9 ms on one core).
  return
      [threads = params_.labelThreads](std::size_t n, std::size_t chunk,
                                       const std::function<void(std::size_t, std::size_t)>& body) {
        forEachChunk(n, chunk, threads, body);
      };
}

std::size_t ProxyCollisionDetector::learnPendingObservations() {
  std::vector<double> values;
  Labels labels;
  {
    const std::lock_guard pending(pendingMutex_);
    values = pendingValues_;
    labels = pendingLabels_;
  }
  if (labels.empty()) return 0;
  trainer_.addPoints(
      Eigen::Map<const Configurations>(values.data(), static_cast<Eigen::Index>(labels.size()),
                                       static_cast<Eigen::Index>(features_.configurationDim())),
      labels, onLabelThreads());
  return labels.size();
}

void ProxyCollisionDetector::dropLearnedObservations(std::size_t count) {
  // New observations are appended: the first `count` are the ones learned.
  const std::lock_guard pending(pendingMutex_);
  const auto values = static_cast<std::ptrdiff_t>(count * features_.configurationDim());
  pendingValues_.erase(pendingValues_.begin(), pendingValues_.begin() + values);
  pendingLabels_.erase(pendingLabels_.begin(),
                       pendingLabels_.begin() + static_cast<std::ptrdiff_t>(count));
}

StepReport ProxyCollisionDetector::learnObservations() {
  const std::lock_guard lock(stepMutex_);
  if (version_ == 0) {
    throw Error("ProxyCollisionDetector::learnObservations() called before initialize()");
  }
  const auto start = Clock::now();
  StepReport report;
  report.observed = learnPendingObservations();
  dropLearnedObservations(report.observed);
  if (report.observed == 0) {
    report.modelVersion = version_;
    return report;
  }
  report.calibration = calibratedModel().calibration;  // kept: nothing new was held out
  report.update = trainer_.update(params_.trainThreads);
  return finish(report, start, Configurations(0, 0), {}, params_.trainThreads);
}

void ProxyCollisionDetector::addObservations(const Dataset& answers) {
  if (answers.size() == 0) return;
  const std::size_t dim = features_.configurationDim();
  checkLabelled(answers, dim, "observation");
  const std::lock_guard pending(pendingMutex_);
  const std::size_t room = params_.maxPendingObservations > pendingLabels_.size()
                               ? params_.maxPendingObservations - pendingLabels_.size()
                               : 0;
  const std::size_t taken = std::min(room, answers.size());
  for (std::size_t i = 0; i < taken; ++i) {
    const auto row = answers.points.row(static_cast<Eigen::Index>(i));
    pendingValues_.insert(pendingValues_.end(), row.data(), row.data() + dim);
  }
  pendingLabels_.insert(pendingLabels_.end(), answers.labels.begin(),
                        answers.labels.begin() + static_cast<std::ptrdiff_t>(taken));
  dropped_ += answers.size() - taken;
}

std::size_t ProxyCollisionDetector::droppedObservations() const {
  const std::lock_guard pending(pendingMutex_);
  return dropped_;
}

std::shared_ptr<const Model> ProxyCollisionDetector::model() const {
  return calibratedModel().model;
}

CalibratedModel ProxyCollisionDetector::calibratedModel() const {
  CalibratedModel current;
  {
    const std::lock_guard lock(modelMutex_);
    current = published_;
  }
  if (!current.model) throw Error("ProxyCollisionDetector: no model before initialize()");
  return current;
}

void ProxyCollisionDetector::startBackground(std::function<void(const StepReport&)> onStep,
                                             std::chrono::nanoseconds minPeriod) {
  if (minPeriod.count() < 0) throw InvalidArgument("startBackground: minPeriod must be >= 0");
  if (worker_.joinable()) throw Error("ProxyCollisionDetector: background updates already running");
  {
    const std::lock_guard lock(stepMutex_);
    if (version_ == 0) throw Error("ProxyCollisionDetector: initialize() before startBackground()");
  }
  workerError_ = nullptr;
  {
    const std::lock_guard lock(healthMutex_);
    health_ = BackgroundHealth{};
  }
  worker_ =
      std::jthread([this, onStep = std::move(onStep), minPeriod](const std::stop_token& stop) {
        const auto pauseUntil = [&](Clock::time_point until) {
          std::unique_lock lock(pauseMutex_);
          pause_.wait_until(lock, stop, until, [] { return false; });
        };
        try {
          while (!stop.stop_requested()) {
            const auto began = Clock::now();
            StepReport report;
            try {
              report = runStep(stop, 1);
            } catch (const LabellingStopped&) {
              break;
            } catch (const OracleFault& fault) {
              {
                const std::lock_guard lock(healthMutex_);
                ++health_.faults;
                ++health_.consecutiveFaults;
                health_.lastFault = fault.what();
              }
              pauseUntil(began + std::max(minPeriod, params_.faultRetryPeriod));
              continue;
            }
            {
              const std::lock_guard lock(healthMutex_);
              ++health_.steps;
              health_.consecutiveFaults = 0;
            }
            if (onStep) onStep(report);
            if (minPeriod.count() > 0) pauseUntil(began + minPeriod);
          }
        } catch (...) {
          workerError_ = std::current_exception();
        }
      });
}

BackgroundHealth ProxyCollisionDetector::backgroundHealth() const {
  BackgroundHealth health;
  {
    const std::lock_guard lock(healthMutex_);
    health = health_;
  }
  const std::lock_guard lock(modelMutex_);
  health.modelVersion = published_.version;
  return health;
}

void ProxyCollisionDetector::stopBackground() {
  worker_.request_stop();
  if (worker_.joinable()) worker_.join();
  worker_ = {};
  if (auto error = std::exchange(workerError_, nullptr)) std::rethrow_exception(error);
}

ProxyParams defaultProxyParams(FeatureKind kind, bool selfCollisionLabels) {
  ProxyParams params;
  params.train = defaultTrainParams(kind, selfCollisionLabels);
  if (kind == FeatureKind::Kinematic) {
    params.activeLearning.maxSamples = 2500;
    params.activeLearning.exploitationShare = 0.2;
    params.coldStart = true;
  }
  return params;
}

ProxyParams withWarmStart(ProxyParams params) {
  params.coldStart = false;
  params.activeLearning.exploitationShare = 1;
  return params;
}

StepReport trainStatic(ProxyCollisionDetector& proxy, std::size_t samples, std::size_t updates) {
  const auto began = Clock::now();
  StepReport report = proxy.initialize(samples);
  for (std::size_t u = 0; u < updates; ++u) report = proxy.step();
  report.total = Clock::now() - began;
  return report;
}

Dataset answersMissedBy(const Model& model, const Dataset& answers) {
  Dataset missed;
  missed.points.resize(0, static_cast<Eigen::Index>(model.dim()));
  if (answers.size() == 0) return missed;
  const Eigen::VectorXd scores = model.scoreBatch(answers.points);
  std::vector<Eigen::Index> rows;
  for (std::size_t i = 0; i < answers.size(); ++i) {
    if ((scores[static_cast<Eigen::Index>(i)] > 0) != (answers.labels[i] > 0)) {
      rows.push_back(static_cast<Eigen::Index>(i));
      missed.labels.push_back(answers.labels[i]);
    }
  }
  missed.points = answers.points(rows, Eigen::all);
  return missed;
}

}  // namespace fastron
