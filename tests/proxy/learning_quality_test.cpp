// What the proxy's defaults buy, measured on a seeded scene with the real exact checker: slow
// statistical tests (hundreds of updates) that run in the release build only (label
// no-sanitizer). Their code paths run under the sanitizers and ThreadSanitizer in fcl_oracle_test
// and proxy_test; here only the models' quality is asserted.

#include <gtest/gtest.h>

#include "fastron/core/active_learning.h"
#include "fastron/core/metrics.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/proxy/labelling.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron {
namespace {

TEST(LearningQuality, UpdatesFromZeroWeightsKeepFindingCollisionsAsBoxesWander) {
  // Baxter among three boxes on random walks, 200 updates of 2500 new points: from their last
  // weights (the paper's warm start) the models call free more of the colliding configurations
  // than models that relearn from zero weights on the same kind of points (as written: TPR 0.881
  // against 0.951, accuracy 0.987 against 0.981; docs/algorithms.md).
  const Robot baxter = loadRobot("baxter");
  const Scene start = loadScene(dataDirectory() / "scenes" / "baxter_three_boxes.yaml");
  const auto meanRates = [&](bool coldStart) {
    Scene scene = start;
    auto fcl = std::make_shared<FclChecker>(baxter, scene);
    ProxyParams params = defaultProxyParams(FeatureKind::Kinematic);
    params.train.maxIterations = 20000;
    params.coldStart = coldStart;
    params.calibrationSamples = 0;
    ProxyCollisionDetector proxy(fcl, robotFeatures(baxter, FeatureKind::Kinematic), params);
    proxy.initialize(3000);
    Rng rng(5);
    double accuracy = 0, tpr = 0;
    constexpr int kUpdates = 200, kEvery = 20;
    for (int t = 1; t <= kUpdates; ++t) {
      scene.step();
      fcl->setScene(scene);
      proxy.step();
      if (t % kEvery != 0) continue;
      const Configurations test = uniformConfigurations(baxter.limits(), 1000, rng);
      const ConfusionCounts counts =
          evaluate(*proxy.model(), test, labelConfigurations(*fcl, test));
      accuracy += counts.accuracy() / (kUpdates / kEvery);
      tpr += counts.tpr() / (kUpdates / kEvery);
    }
    return std::pair{accuracy, tpr};
  };
  const auto [warmAccuracy, warmTpr] = meanRates(false);
  const auto [coldAccuracy, coldTpr] = meanRates(true);
  EXPECT_GE(coldTpr, warmTpr + 0.03);
  EXPECT_GE(coldAccuracy, warmAccuracy - 0.02);
}

}  // namespace
}  // namespace fastron
