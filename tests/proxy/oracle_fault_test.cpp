// Faults injected into the oracle: one that throws, one that hangs past the labelling deadline,
// one that answers the same configuration both ways. The detector keeps serving its last good
// model, reports the fault, and recovers when the oracle does; stopBackground always returns.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <thread>

#include "fastron/core/dataset.h"
#include "fastron/core/error.h"
#include "fastron/proxy/labelling.h"
#include "fastron/proxy/proxy_collision_detector.h"
#include "temp_dir.h"  // messageOf
#include "test_worlds.h"

namespace fastron {
namespace {

using namespace std::chrono_literals;
using ::testing::HasSubstr;

enum class Fault { None, Throw, Hang, Alternate };

const char* nameOf(Fault fault) {
  switch (fault) {
    case Fault::Throw:
      return "Throws";
    case Fault::Hang:
      return "HangsPastTheDeadline";
    case Fault::Alternate:
      return "AnswersBothWays";
    case Fault::None:
      break;
  }
  return "None";
}
void PrintTo(Fault fault, std::ostream* out) {
  *out << nameOf(fault);
}

/// A disc of radius 0.5 at the origin of [-1, 1]^2, with a fault switched on and off at will.
class FaultyOracle final : public CollisionChecker {
 public:
  std::size_t dof() const override { return 2; }
  std::string name() const override { return "faulty"; }
  std::atomic<Fault> fault{Fault::None};
  /// Calls after this many (counted from when it is set) throw.
  std::atomic<std::uint64_t> failAfter{std::numeric_limits<std::uint64_t>::max()};

 protected:
  bool check(const double* q) const override {
    const bool truth = q[0] * q[0] + q[1] * q[1] < 0.25;
    if (failAfter.load() != std::numeric_limits<std::uint64_t>::max() &&
        calls_.fetch_add(1) >= failAfter.load()) {
      throw Error("lost the scene");
    }
    switch (fault.load()) {
      case Fault::Throw:
        throw Error("lost the scene");
      case Fault::Hang:
        std::this_thread::sleep_for(20ms);
        return truth;
      case Fault::Alternate: {
        // Each labelling thread alternates its own answers, so the two calls of a repeated row
        // (one thread, one after the other) always differ. (One counter for all threads let the
        // other thread's calls in between make them agree: all eight repeated rows did, once in
        // a CI run.)
        thread_local std::uint64_t flips = 0;
        return (flips++ % 2 == 0) != truth;
      }
      case Fault::None:
        break;
    }
    return truth;
  }

 private:
  mutable std::atomic<std::uint64_t> calls_{0};
};

ProxyParams faultParams() {
  ProxyParams p;
  p.train.kernel.gamma = 10;
  p.train.beta = 5;
  p.activeLearning = {200, 4, 0};
  p.calibrationSamples = 200;
  p.labelThreads = 2;
  p.labelDeadline = 200ms;
  p.faultRetryPeriod = 5ms;
  return p;
}

/// Waits (10 s at most) until `done` holds.
template <class Done>
bool eventually(Done done) {
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

class OracleFaults : public ::testing::TestWithParam<Fault> {};

TEST_P(OracleFaults, StepFailsWithoutChangingTheModel) {
  auto oracle = std::make_shared<FaultyOracle>();
  ProxyCollisionDetector proxy(oracle, JointLimits::unitBox(2), faultParams());
  proxy.initialize(500);
  const CalibratedModel before = proxy.calibratedModel();
  oracle->fault = GetParam();
  const std::string message = test::messageOf<OracleFault>([&] { proxy.step(); });
  EXPECT_THAT(message, HasSubstr("oracle 'faulty'"));
  const CalibratedModel after = proxy.calibratedModel();
  EXPECT_EQ(after.model, before.model);
  EXPECT_EQ(after.version, before.version);
  oracle->fault = Fault::None;
  EXPECT_EQ(proxy.step().modelVersion, before.version + 1);
}

// The points held out for the band are labelled last (after Algorithm 1, with one labelling
// thread): a fault there must undo the training the step already did.
TEST(OracleFaultsAfterTraining, LeaveTheTrainerAsItWas) {
  auto oracle = std::make_shared<FaultyOracle>();
  ProxyParams params = faultParams();
  params.labelThreads = 1;
  ProxyCollisionDetector proxy(oracle, JointLimits::unitBox(2), params);
  proxy.initialize(500);
  const CalibratedModel before = proxy.calibratedModel();
  const std::size_t support = before.model->supportCount();
  // Exact answers waiting to be learned: the failed step must leave them to the next one.
  Configurations observed(3, 2);
  observed << 0.1, 0.1, 0.9, 0.9, -0.2, 0.3;
  proxy.addObservations(Dataset{observed, Labels{1, -1, 1}, {}});
  // Support set, 200 active-learning points and the repeated rows, then the held-out points.
  oracle->failAfter = support + 200 + params.repeatedLabels + 10;
  EXPECT_THAT(test::messageOf<OracleFault>([&] { proxy.step(); }), HasSubstr("lost the scene"));
  EXPECT_EQ(proxy.calibratedModel().model, before.model);
  oracle->failAfter = std::numeric_limits<std::uint64_t>::max();
  // The next step relabels the support set the published model has, not a trained-on one, and
  // learns the observations.
  const StepReport next = proxy.step();
  EXPECT_EQ(next.labelled, support + 200 + 200 + params.repeatedLabels);
  EXPECT_EQ(next.observed, 3u);
  EXPECT_EQ(proxy.step().observed, 0u);  // learned once
}

TEST_P(OracleFaults, BackgroundServesTheLastGoodModelAndRecovers) {
  auto oracle = std::make_shared<FaultyOracle>();
  ProxyCollisionDetector proxy(oracle, JointLimits::unitBox(2), faultParams());
  proxy.initialize(500);
  const std::uint64_t calls = oracle->callCount();
  oracle->fault = GetParam();
  const CalibratedModel lastGood = proxy.calibratedModel();
  proxy.startBackground();
  ASSERT_TRUE(eventually([&] { return proxy.backgroundHealth().faults >= 2; }));
  BackgroundHealth health = proxy.backgroundHealth();
  EXPECT_EQ(health.steps, 0u);
  EXPECT_GE(health.consecutiveFaults, 2u);
  EXPECT_THAT(health.lastFault, HasSubstr("oracle 'faulty'"));
  EXPECT_EQ(proxy.calibratedModel().model, lastGood.model);  // still served
  EXPECT_GT(oracle->callCount(), calls);

  oracle->fault = Fault::None;
  ASSERT_TRUE(eventually([&] { return proxy.backgroundHealth().steps >= 2; }));
  health = proxy.backgroundHealth();
  EXPECT_EQ(health.consecutiveFaults, 0u);
  EXPECT_GT(proxy.calibratedModel().version, lastGood.version);

  // Faulty again when stopped: stopBackground returns at once, without an error.
  oracle->fault = GetParam();
  const auto stopping = std::chrono::steady_clock::now();
  EXPECT_NO_THROW(proxy.stopBackground());
  EXPECT_LT(std::chrono::steady_clock::now() - stopping, 2s);
}

INSTANTIATE_TEST_SUITE_P(, OracleFaults,
                         ::testing::Values(Fault::Throw, Fault::Hang, Fault::Alternate),
                         [](const auto& info) { return std::string(nameOf(info.param)); });

LabelGuard withRepeatedRows(std::size_t rows) {
  LabelGuard guard;
  guard.repeatedRows = rows;
  return guard;
}

TEST(OracleFaultMessages, NameWhatTheOracleDid) {
  FaultyOracle oracle;
  const Configurations q = test::uniformPoints(400, 2, 5);
  oracle.fault = Fault::Throw;
  EXPECT_THAT(test::messageOf<OracleFault>([&] { labelConfigurations(oracle, q, 2); }),
              HasSubstr("oracle 'faulty' failed: lost the scene"));
  oracle.fault = Fault::Hang;
  EXPECT_THAT(test::messageOf<OracleFault>([&] {
                LabelGuard guard;
                guard.deadline = std::chrono::steady_clock::now() + 30ms;
                labelConfigurations(oracle, q, 2, guard);
              }),
              HasSubstr("passed its labelling deadline (400 configurations)"));
  oracle.fault = Fault::Alternate;
  EXPECT_THAT(
      test::messageOf<OracleFault>([&] { labelConfigurations(oracle, q, 1, withRepeatedRows(4)); }),
      HasSubstr("gave two different answers for the same configuration"));
  oracle.fault = Fault::None;
  EXPECT_EQ(labelConfigurations(oracle, q, 2, withRepeatedRows(400)),
            labelConfigurations(oracle, q, 1));
}

// A stop requested while the oracle hangs ends the labelling after the calls under way.
TEST(OracleFaultMessages, StopEndsAHangingLabelling) {
  FaultyOracle oracle;
  oracle.fault = Fault::Hang;
  std::stop_source stop;
  std::jthread stopper([&] {
    std::this_thread::sleep_for(50ms);
    stop.request_stop();
  });
  const auto began = std::chrono::steady_clock::now();
  EXPECT_THROW(labelConfigurations(oracle, test::uniformPoints(1000, 2, 6), 2,
                                   {.deadline = std::chrono::steady_clock::time_point::max(),
                                    .repeatedRows = 0,
                                    .stop = stop.get_token()}),
               LabellingStopped);
  EXPECT_LT(std::chrono::steady_clock::now() - began, 2s);  // not 1000 * 20 ms / 2
}

}  // namespace
}  // namespace fastron
