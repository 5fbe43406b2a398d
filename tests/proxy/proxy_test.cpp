// The pipeline: initialize / step over an oracle, determinism, background updates with
// concurrent queries (also run under ThreadSanitizer: ./dev.sh test).

#include "fastron/proxy/proxy_collision_detector.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/proxy/labelling.h"
#include "temp_dir.h"
#include "test_worlds.h"

namespace fastron {
namespace {

// A ball world whose balls move; reads and moves are synchronised, as a real scene must be.
class MovingBalls {
 public:
  MovingBalls(std::size_t dim, std::uint64_t seed)
      : world_(test::BallWorld::random(dim, 3, 0.45, seed)) {}
  bool inCollision(const double* q) const {
    const std::lock_guard lock(mutex_);
    return world_.inCollision(q);
  }
  void move(double step) {
    const std::lock_guard lock(mutex_);
    world_.move(step);
  }
  std::shared_ptr<const CollisionChecker> checker(std::size_t dim) {
    return std::make_shared<FunctionChecker>("balls", dim,
                                             [this](const double* q) { return inCollision(q); });
  }

 private:
  mutable std::mutex mutex_;
  test::BallWorld world_;
};

ProxyParams params(double gamma, std::uint64_t seed = 1) {
  ProxyParams p;
  p.train.kernel.gamma = gamma;
  p.train.beta = 5;
  p.activeLearning = {300, 4, 0};
  p.seed = seed;
  return p;
}

/// Points a step held out of its model to calibrate the band.
std::size_t heldOut(const StepReport& report) {
  return report.calibration.colliding + report.calibration.free;
}

double accuracy(const Model& model, const MovingBalls& world, std::size_t dim) {
  const Configurations q = test::uniformPoints(4000, dim, 99);
  Labels y(static_cast<std::size_t>(q.rows()));
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    y[static_cast<std::size_t>(i)] = world.inCollision(q.row(i).data()) ? 1 : -1;
  return evaluate(model, q, y).accuracy();
}

TEST(Labelling, ParallelLabelsEqualSerialLabels) {
  MovingBalls world(3, 1);
  const auto checker = world.checker(3);
  const Configurations q = test::uniformPoints(1001, 3, 2);
  const Labels serial = labelConfigurations(*checker, q, 1);
  EXPECT_EQ(labelConfigurations(*checker, q, 2), serial);
  EXPECT_EQ(labelConfigurations(*checker, q, 7), serial);
  EXPECT_EQ(checker->callCount(), 3 * 1001u);
  EXPECT_TRUE(labelConfigurations(*checker, Configurations(0, 3)).empty());
}

// A checker that counts how it is asked: rows per call of checkEach.
class RunCountingChecker final : public CollisionChecker {
 public:
  explicit RunCountingChecker(std::chrono::microseconds perCheck) : perCheck_(perCheck) {}
  std::string name() const override { return "counting"; }
  std::size_t dof() const override { return 2; }
  mutable std::atomic<std::size_t> runs{0}, longestRun{0};

 protected:
  bool check(const double* q) const override {
    if (perCheck_.count() > 0) std::this_thread::sleep_for(perCheck_);
    return q[0] > 0;
  }
  void checkEach(const double* q, std::size_t n, std::uint8_t* out) const override {
    ++runs;
    std::size_t longest = longestRun.load();
    while (n > longest && !longestRun.compare_exchange_weak(longest, n)) {
    }
    CollisionChecker::checkEach(q, n, out);
  }

 private:
  std::chrono::microseconds perCheck_;
};

// Labelling asks a quick checker for runs of rows (one read of its world and one scratch each,
// FclChecker::checkEach), and a slow one for one row at a time, so that a stop or a deadline is
// seen between its calls. The labels are the same either way.
TEST(Labelling, AsksAQuickCheckerForRunsAndASlowOneRowByRow) {
  const Configurations q = test::uniformPoints(1000, 2, 4);
  const RunCountingChecker quick(std::chrono::microseconds(0));
  const Labels labels = labelConfigurations(quick, q, 2);
  EXPECT_EQ(quick.callCount(), 1000u);
  EXPECT_GT(quick.longestRun.load(), 1u);
  EXPECT_LE(quick.longestRun.load(), 16u);  // a chunk
  // Two calls per chunk of 16 (its first row, then the rest): 126; a row per call would be 1000.
  // (A first call that a busy machine preempts past 20 us sends its chunk row by row.)
  EXPECT_LE(quick.runs.load(), 500u);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    EXPECT_EQ(labels[static_cast<std::size_t>(i)], q(i, 0) > 0 ? 1 : -1) << "row " << i;
  }
  const RunCountingChecker slow(std::chrono::microseconds(100));
  EXPECT_EQ(labelConfigurations(slow, q.topRows(64), 2),
            Labels(labels.begin(), labels.begin() + 64));
  EXPECT_EQ(slow.longestRun.load(), 1u);
  EXPECT_EQ(slow.runs.load(), 64u);
}

TEST(Labelling, CheckerErrorsReachTheCaller) {
  const FunctionChecker failing("failing", 2, [](const double* q) -> bool {
    if (q[0] > 0.9) throw Error("sensor offline");
    return false;
  });
  EXPECT_THROW(labelConfigurations(failing, test::uniformPoints(500, 2, 3), 2), Error);
}

TEST(ProxyCollisionDetector, TracksAMovingWorld) {
  MovingBalls world(2, 4);
  ProxyCollisionDetector proxy(world.checker(2), JointLimits::unitBox(2), params(30));
  const StepReport init = proxy.initialize(2000);
  EXPECT_EQ(init.labelled, 3000u + 8);  // + the repeated labels
  EXPECT_EQ(heldOut(init), 1000u);      // ProxyParams::calibrationSamples, for the band
  EXPECT_EQ(init.update.stopReason, StopReason::Converged);
  EXPECT_GT(accuracy(*proxy.model(), world, 2), 0.95);
  for (int t = 0; t < 10; ++t) {
    world.move(0.02);
    const std::size_t support = proxy.model()->supportCount();
    const StepReport report = proxy.step();
    // |S| + A_max collision checks (Sec. II-F), and the points held out for the band.
    EXPECT_EQ(report.labelled, support + 300 + 1000 + 8);
    EXPECT_EQ(report.added, 300u);
    EXPECT_EQ(heldOut(report), 1000u);
    EXPECT_EQ(report.modelVersion, static_cast<std::uint64_t>(t + 2));
  }
  EXPECT_GT(accuracy(*proxy.model(), world, 2), 0.95);
}

// Each published model comes with a band calibrated on points it did not learn; on fresh
// configurations of the world, few colliding ones fall below it, and the pair is consistent.
TEST(ProxyCollisionDetector, PublishesABandCalibratedOnPointsItDidNotLearn) {
  MovingBalls world(3, 6);
  ProxyParams p = params(10);
  p.band = {.missRate = 0.005, .falseAlarmRate = 0.05};
  // About 11% of the space collides: 4000 held-out points give ~440 colliding ones, so the band
  // sits at the third-lowest colliding score, not the lowest. With the default 1000 (~110
  // colliding, the band at the lowest) 2.1% of fresh colliding configurations fell below it.
  p.calibrationSamples = 4000;
  ProxyCollisionDetector proxy(world.checker(3), JointLimits::unitBox(3), p);
  proxy.initialize(2000);
  StepReport last;
  for (int t = 0; t < 5; ++t) {
    world.move(0.01);
    last = proxy.step();
  }
  const CalibratedModel current = proxy.calibratedModel();
  EXPECT_EQ(current.model, proxy.model());
  EXPECT_EQ(current.calibration.band.lower, last.calibration.band.lower);
  EXPECT_LE(current.calibration.bandMissRate, 0.005);
  EXPECT_LE(current.calibration.band.lower, 0);
  EXPECT_GE(current.calibration.band.upper, 0);

  const Configurations q = test::uniformPoints(20000, 3, 21);
  const Eigen::VectorXd scores = current.model->scoreBatch(q);
  std::size_t colliding = 0, missed = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    if (!world.inCollision(q.row(i).data())) continue;
    ++colliding;
    if (scores[i] < current.calibration.band.lower) ++missed;
  }
  ASSERT_GT(colliding, 1000u);
  EXPECT_LT(static_cast<double>(missed) / static_cast<double>(colliding), 0.01);

  p.band.missRate = 2;
  EXPECT_THROW(ProxyCollisionDetector(world.checker(3), JointLimits::unitBox(3), p),
               InvalidArgument);
  p.band.missRate = 0.005;
  p.calibrationSamples = 0;
  ProxyCollisionDetector uncalibrated(world.checker(3), JointLimits::unitBox(3), p);
  EXPECT_EQ(heldOut(uncalibrated.initialize(500)), 0u);
  EXPECT_EQ(uncalibrated.calibratedModel().calibration.band.lower, 0);
}

// In a world that stands still, the observations are learned at once, without a single oracle
// call, and the band stays the calibrated one.
TEST(ProxyCollisionDetector, LearnsObservationsWithoutTheOracle) {
  MovingBalls world(2, 4);
  const auto checker = world.checker(2);
  ProxyCollisionDetector proxy(checker, JointLimits::unitBox(2), params(30));
  EXPECT_THROW(proxy.learnObservations(), Error);
  proxy.initialize(300);
  const auto before = proxy.calibratedModel();
  EXPECT_EQ(proxy.learnObservations().observed, 0u);  // nothing waiting: the same model
  EXPECT_EQ(proxy.model(), before.model);

  const Configurations probe = test::uniformPoints(5000, 2, 77);
  Dataset answers;
  answers.points = probe;
  for (Eigen::Index i = 0; i < probe.rows(); ++i) {
    answers.labels.push_back(world.inCollision(probe.row(i).data()) ? 1 : -1);
  }
  const Dataset missed = answersMissedBy(*before.model, answers);
  ASSERT_GT(missed.size(), 20u);
  proxy.addObservations(missed);
  const std::uint64_t calls = checker->callCount();
  const StepReport report = proxy.learnObservations();
  EXPECT_EQ(checker->callCount(), calls) << "no oracle call";
  EXPECT_EQ(report.observed, missed.size());
  EXPECT_EQ(report.modelVersion, 2u);
  EXPECT_EQ(proxy.calibratedModel().calibration.band.lower, before.calibration.band.lower);
  ASSERT_EQ(report.update.stopReason, StopReason::Converged);
  for (std::size_t k = 0; k < missed.size(); ++k) {
    const Eigen::Index row = static_cast<Eigen::Index>(k);
    EXPECT_EQ(proxy.model()->inCollision(missed.points.row(row).data()), missed.labels[k] > 0);
  }
}

// initialize(labelled): the first model from labels the caller has (one labelling shared by
// models on other features), without the oracle; a step after it asks the oracle as usual.
TEST(ProxyCollisionDetector, InitializesFromLabelsItIsGivenWithoutTheOracle) {
  MovingBalls world(2, 4);
  const auto checker = world.checker(2);
  ProxyCollisionDetector proxy(checker, JointLimits::unitBox(2), params(30));
  Dataset labelled;
  labelled.points = test::uniformPoints(800, 2, 5);
  for (Eigen::Index i = 0; i < labelled.points.rows(); ++i) {
    labelled.labels.push_back(world.inCollision(labelled.points.row(i).data()) ? 1 : -1);
  }
  const StepReport report = proxy.initialize(labelled);
  EXPECT_EQ(checker->callCount(), 0u) << "no oracle call";
  EXPECT_EQ(report.added, labelled.size());
  EXPECT_EQ(report.labelled, 0u);
  EXPECT_EQ(report.modelVersion, 1u);
  ASSERT_EQ(report.update.stopReason, StopReason::Converged);
  for (std::size_t k = 0; k < labelled.size(); ++k) {
    const Eigen::Index row = static_cast<Eigen::Index>(k);
    EXPECT_EQ(proxy.model()->inCollision(labelled.points.row(row).data()), labelled.labels[k] > 0);
  }
  EXPECT_GT(accuracy(*proxy.model(), world, 2), 0.9);
  proxy.step();
  EXPECT_GT(checker->callCount(), 0u);

  ProxyCollisionDetector fresh(checker, JointLimits::unitBox(2), params(30));
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] { fresh.initialize(Dataset{}); }),
              ::testing::HasSubstr("no labelled configurations"));
  Dataset wide = labelled;
  wide.points = test::uniformPoints(800, 3, 5);
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] { fresh.initialize(wide); }),
              ::testing::HasSubstr("labelled configurations have 3 columns"));
  Dataset holed = labelled;
  holed.points(4, 1) = std::nan("");
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] { fresh.initialize(holed); }),
              ::testing::HasSubstr("finite"));
  Dataset unlabelled = labelled;
  unlabelled.labels[2] = 0;
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] { fresh.initialize(unlabelled); }),
              ::testing::HasSubstr("labelled configuration 2 has label 0, expected +1 or -1"));
  EXPECT_THROW(fresh.model(), Error) << "a refused set leaves no model";
}

TEST(ProxyCollisionDetector, SameSeedSameModel) {
  auto run = [](std::uint64_t seed) {
    MovingBalls world(3, 5);
    ProxyCollisionDetector proxy(world.checker(3), JointLimits::unitBox(3), params(10, seed));
    proxy.initialize(1500);
    for (int t = 0; t < 4; ++t) {
      world.move(0.03);
      proxy.step();
    }
    return proxy.model();
  };
  const auto a = run(42), b = run(42), c = run(43);
  EXPECT_EQ(a->supportConfigurations(), b->supportConfigurations());
  EXPECT_EQ(a->weights(), b->weights());
  // Another seed, another model (compared by size first: Eigen compares equal shapes only).
  EXPECT_TRUE(a->supportConfigurations().rows() != c->supportConfigurations().rows() ||
              a->supportConfigurations() != c->supportConfigurations());
}

// With ProxyParams::pointField, each published model of point terms only carries its point field
// and answers as the full sum.
TEST(ProxyCollisionDetector, PublishesModelsOfPointTermsWithTheirPointField) {
  MovingBalls world(3, 7);
  ProxyParams p = params(30);
  p.train.kernel.block = 3;
  p.train.kernel.wholeShare = 0;
  p.pointField = true;
  ProxyCollisionDetector proxy(world.checker(3), JointLimits::unitBox(3), p);
  proxy.initialize(3000);
  for (int t = 0; t < 3; ++t) {
    world.move(0.02);
    proxy.step();
    const auto model = proxy.model();
    ASSERT_NE(model->pointField(), nullptr) << "step " << t;
    const Configurations q = test::uniformPoints(2000, 3, 70 + t);
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      ASSERT_EQ(model->inCollision(q.row(i).data()), model->score(q.row(i).data()) > 0);
    }
  }
  p.pointField = false;  // the same pipeline without: no field
  ProxyCollisionDetector plain(world.checker(3), JointLimits::unitBox(3), p);
  plain.initialize(3000);
  EXPECT_EQ(plain.model()->pointField(), nullptr);
}

// In a world that stands still the support set's labels cannot change: without relabelling it,
// steps make the same model with as many fewer oracle calls as the support set has points.
TEST(ProxyCollisionDetector, AWorldThatStandsStillNeedsNoRelabelling) {
  MovingBalls world(3, 5);
  ProxyParams relabelling = params(10, 7);
  relabelling.coldStart = false;
  ProxyParams still = relabelling;
  still.relabelSupport = false;
  ProxyCollisionDetector a(world.checker(3), JointLimits::unitBox(3), relabelling);
  ProxyCollisionDetector b(world.checker(3), JointLimits::unitBox(3), still);
  a.initialize(1500);
  b.initialize(1500);
  for (int t = 0; t < 3; ++t) {
    const std::size_t support = b.model()->supportCount();
    ASSERT_EQ(a.model()->supportCount(), support);
    const StepReport withRelabelling = a.step(), without = b.step();
    EXPECT_EQ(withRelabelling.labelled, without.labelled + support) << "step " << t;
    EXPECT_EQ(a.model()->supportConfigurations(), b.model()->supportConfigurations());
    EXPECT_EQ(a.model()->weights(), b.model()->weights());
  }
  // Where the world moves, relabelling is what keeps the model up to date: the default.
  EXPECT_TRUE(ProxyParams{}.relabelSupport);
}

// Learning from verification: the answers given to addObservations are learned at the next step,
// and (Algorithm 1 converging) every one of them is then classified as labelled. Here they are
// deliberately the model's own misses, so they must change its answers.
TEST(ProxyCollisionDetector, LearnsTheObservationsItIsGiven) {
  MovingBalls world(2, 4);
  ProxyParams p = params(30);
  p.maxPendingObservations = 400;
  ProxyCollisionDetector proxy(world.checker(2), JointLimits::unitBox(2), p);
  proxy.initialize(300);  // a coarse model: it misses some of what it is asked next
  const Configurations probe = test::uniformPoints(5000, 2, 77);
  Dataset misses;
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i = 0; i < probe.rows() && rows.size() < 300; ++i) {
    const bool hit = world.inCollision(probe.row(i).data());
    if (hit != proxy.model()->inCollision(probe.row(i).data())) rows.push_back(i);
  }
  ASSERT_GT(rows.size(), 20u) << "the test needs a model that misses";
  // answersMissedBy finds the same misses among the rows looked at.
  Dataset looked;
  looked.points = probe.topRows(rows.back() + 1);
  for (Eigen::Index i = 0; i <= rows.back(); ++i) {
    looked.labels.push_back(world.inCollision(probe.row(i).data()) ? 1 : -1);
  }
  const Dataset found = answersMissedBy(*proxy.model(), looked);
  ASSERT_EQ(found.size(), rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(found.points.row(static_cast<Eigen::Index>(k)), probe.row(rows[k]));
    EXPECT_EQ(found.labels[k], looked.labels[static_cast<std::size_t>(rows[k])]);
  }
  misses.points = probe(rows, Eigen::all);
  for (const Eigen::Index i : rows) {
    misses.labels.push_back(world.inCollision(probe.row(i).data()) ? 1 : -1);
  }
  proxy.addObservations(misses);
  const std::size_t support = proxy.model()->supportCount();
  const StepReport report = proxy.step();
  EXPECT_EQ(report.observed, rows.size());
  EXPECT_EQ(report.labelled, support + p.calibrationSamples + report.added + p.repeatedLabels)
      << "observations are not labelled again";
  ASSERT_EQ(report.update.stopReason, StopReason::Converged);
  const auto model = proxy.model();
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(model->inCollision(misses.points.row(static_cast<Eigen::Index>(k)).data()),
              misses.labels[k] > 0)
        << "observation " << k;
  }
  EXPECT_EQ(proxy.step().observed, 0u) << "observations are learned once";

  // The queue is bounded: beyond maxPendingObservations answers are dropped and counted.
  proxy.addObservations(misses);
  proxy.addObservations(misses);
  EXPECT_EQ(proxy.droppedObservations(), 2 * rows.size() - 400);
  EXPECT_EQ(proxy.step().observed, 400u);

  Dataset bad = misses;
  bad.labels[3] = 0;
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] { proxy.addObservations(bad); }),
              ::testing::HasSubstr("observation 3 has label 0, expected +1 or -1"));
  bad = misses;
  bad.points(1, 1) = std::nan("");
  EXPECT_THROW(proxy.addObservations(bad), InvalidArgument);
  bad.points = Configurations::Zero(static_cast<Eigen::Index>(misses.size()), 3);
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] { proxy.addObservations(bad); }),
              ::testing::HasSubstr("observations have 3 columns"));
}

TEST(ProxyCollisionDetector, RefusesMisuse) {
  MovingBalls world(2, 6);
  EXPECT_THROW(ProxyCollisionDetector(world.checker(3), JointLimits::unitBox(2)), InvalidArgument);
  EXPECT_THROW(ProxyCollisionDetector(nullptr, JointLimits::unitBox(2)), InvalidArgument);
  ProxyCollisionDetector proxy(world.checker(2), JointLimits::unitBox(2), params(30));
  EXPECT_THROW(proxy.model(), Error);
  EXPECT_THROW(proxy.step(), Error);
  EXPECT_THROW(proxy.startBackground(), Error);
}

// Readers query snapshots while the background thread publishes new models: a snapshot never
// changes under its reader and is always complete.
TEST(ProxyCollisionDetector, ConcurrentQueriesDuringBackgroundUpdates) {
  MovingBalls world(3, 7);
  ProxyParams p = params(10);
  p.labelThreads = 2;
  ProxyCollisionDetector proxy(world.checker(3), JointLimits::unitBox(3), p);
  proxy.initialize(1000);

  std::atomic<int> steps{0};
  proxy.startBackground([&](const StepReport&) { ++steps; });
  std::atomic<bool> done{false};
  std::atomic<std::size_t> queries{0}, distinctModels{0};
  auto reader = [&](std::uint64_t seed) {
    const Configurations q = test::uniformPoints(64, 3, seed);
    const Model* last = nullptr;
    while (!done) {
      const std::shared_ptr<const Model> model = proxy.model();
      distinctModels += model.get() != last;
      last = model.get();
      const Eigen::VectorXd first = model->scoreBatch(q);
      for (Eigen::Index i = 0; i < q.rows(); ++i) {
        ASSERT_EQ(model->score(q.row(i).data()), first[i]);  // the snapshot did not change
      }
      queries += static_cast<std::size_t>(q.rows());
    }
  };
  {
    std::jthread r1(reader, 1), r2(reader, 2);
    // Until the readers have seen new models arrive (10 s at most, however loaded the machine).
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while ((steps < 8 || distinctModels <= 4) && std::chrono::steady_clock::now() < deadline) {
      world.move(0.01);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    done = true;
  }
  proxy.stopBackground();
  EXPECT_FALSE(proxy.backgroundRunning());
  EXPECT_GE(proxy.model()->supportCount(), 1u);
  EXPECT_GT(queries.load(), 0u);
  EXPECT_GT(distinctModels.load(), 4u);  // the readers saw new models arrive
  // Synchronous steps work again after stopping.
  EXPECT_NO_THROW(proxy.step());
}

// A planar arm of two unit links whose joints are the first two coordinates: the control points
// are the elbow and the tip. Task-space features without any robot library.
class PlanarArm final : public PointKinematics {
 public:
  std::size_t dof() const override { return 2; }
  std::size_t pointCount() const override { return 2; }
  void positions(const double* q, double* out) const override { place(q, out); }
  void positions(const double* q, float* out) const override { place(q, out); }
  KinematicsDescription description() const override {
    return {"planar", {"a", "b"}, {{"upper", {}}, {"lower", {}}}, 42};
  }

 private:
  template <class T>
  static void place(const double* q, T* out) {
    const double pi = 3.14159265358979;
    const double a = pi * q[0], b = a + pi * q[1];
    const double elbow[3] = {std::cos(a), std::sin(a), 0};
    const double tip[3] = {elbow[0] + std::cos(b), elbow[1] + std::sin(b), 0};
    for (int k = 0; k < 3; ++k) {
      out[k] = static_cast<T>(elbow[k]);
      out[3 + k] = static_cast<T>(tip[k]);
    }
  }
};

// The same concurrency, on task-space features: readers map their queries through the shared
// kinematics while the background thread maps its training points.
TEST(ProxyCollisionDetector, ConcurrentQueriesWithTaskSpaceFeatures) {
  MovingBalls world(2, 9);
  ProxyParams p = params(3);  // gamma in 1/m^2: the arm reaches 2 m
  p.labelThreads = 2;
  const FeatureMap features =
      FeatureMap::kinematic(JointLimits::unitBox(2), std::make_shared<PlanarArm>());
  ProxyCollisionDetector proxy(world.checker(2), features, p);
  proxy.initialize(800);
  EXPECT_EQ(proxy.model()->featureDim(), 6u);
  std::atomic<int> steps{0};
  proxy.startBackground([&](const StepReport&) { ++steps; });
  std::atomic<bool> done{false};
  auto reader = [&](std::uint64_t seed) {
    const Configurations q = test::uniformPoints(32, 2, seed);
    while (!done) {
      const std::shared_ptr<const Model> model = proxy.model();
      const Eigen::VectorXd first = model->scoreBatch(q);
      for (Eigen::Index i = 0; i < q.rows(); ++i)
        ASSERT_EQ(model->score(q.row(i).data()), first[i]);
    }
  };
  {
    std::jthread r1(reader, 3), r2(reader, 4);
    // The world moves by the same 0.1 per axis however fast the steps run: moving until the fifth
    // step let a loaded machine carry the balls several tenths, which three still steps could not
    // catch up with (accuracy 0.80-0.89 in 1 of 20 runs beside three busy loops).
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    for (int moves = 0; steps < 5 && std::chrono::steady_clock::now() < deadline; ++moves) {
      if (moves < 10) world.move(0.01);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    done = true;
  }
  proxy.stopBackground();
  EXPECT_GE(steps.load(), 1);
  for (int s = 0; s < 3; ++s) proxy.step();  // the world stands still now
  EXPECT_GT(accuracy(*proxy.model(), world, 2), 0.9);
}

// With a minimum period, steps start at most once per period, and stopping does not wait the
// period out.
TEST(ProxyCollisionDetector, BackgroundStepsKeepTheirMinimumPeriod) {
  using namespace std::chrono_literals;
  MovingBalls world(2, 8);
  ProxyCollisionDetector proxy(world.checker(2), JointLimits::unitBox(2), params(10));
  proxy.initialize(300);
  EXPECT_THROW(proxy.startBackground({}, -1ms), InvalidArgument);

  std::atomic<int> steps{0};
  const auto began = std::chrono::steady_clock::now();
  proxy.startBackground([&](const StepReport&) { ++steps; }, 40ms);
  std::this_thread::sleep_for(400ms);
  proxy.stopBackground();
  const auto elapsed = std::chrono::steady_clock::now() - began;
  EXPECT_GE(steps.load(), 1);
  EXPECT_LE(steps.load(), static_cast<int>(elapsed / 40ms) + 1);

  steps = 0;
  proxy.startBackground([&](const StepReport&) { ++steps; }, 60s);
  while (steps == 0) std::this_thread::yield();
  const auto stopping = std::chrono::steady_clock::now();
  proxy.stopBackground();
  EXPECT_LT(std::chrono::steady_clock::now() - stopping, 10s);
  EXPECT_EQ(steps.load(), 1);
}

// An exception from the caller's own callback is not an oracle fault: it ends the loop, and
// stopBackground() rethrows it. (Oracle faults: oracle_fault_test.cpp.)
TEST(ProxyCollisionDetector, CallbackErrorsAreRethrownOnStop) {
  MovingBalls world(2, 3);
  ProxyCollisionDetector proxy(world.checker(2), JointLimits::unitBox(2), params(10));
  proxy.initialize(300);
  std::atomic<bool> called{false};
  proxy.startBackground([&](const StepReport&) {
    called = true;
    throw InvalidArgument("the caller's own bug");
  });
  while (!called) std::this_thread::yield();
  EXPECT_THROW(proxy.stopBackground(), InvalidArgument);
  EXPECT_FALSE(proxy.backgroundRunning());
}

}  // namespace
}  // namespace fastron
