// The proxy on a real exact checker: parallel labelling with FCL, and the paper's pipeline learning
// Baxter's C-space while the box moves (also runs under ThreadSanitizer in ./dev.sh test; the
// slow statistical comparison of update recipes is in learning_quality_test.cpp).

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

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

TEST(FclOracle, ParallelLabellingEqualsSerial) {
  const Robot baxter = loadRobot("baxter");
  Scene scene;
  scene.add({"box", Box{Eigen::Vector3d::Constant(0.3)}, makePose({0.6, -0.6, 0.2}), std::nullopt});
  const FclChecker fcl(baxter, scene, {.selfCollision = true});
  Rng rng(1);
  const Configurations q = uniformConfigurations(baxter.limits(), 2000, rng);
  EXPECT_EQ(labelConfigurations(fcl, q, 4), labelConfigurations(fcl, q, 1));
}

// The paper's pipeline on a real robot: the proxy learns Baxter's C-space from FCL while the box
// moves, updating in the background as the scene is replaced under the checker.
TEST(FclOracle, ProxyLearnsFromFclWhileTheBoxMoves) {
  Robot baxter = loadRobot("baxter");
  baxter.setActuatedJoints({"right_s0", "right_s1", "right_e0", "right_e1"});
  Scene scene;
  scene.add({"box", Box{Eigen::Vector3d::Constant(0.2)}, makePose({0.6, -0.6, 0.2}),
             RandomWalk{0.01, 0.04,
                        Eigen::AlignedBox3d(Eigen::Vector3d(0.3, -1.0, -0.2),
                                            Eigen::Vector3d(1.0, -0.2, 0.6)),
                        3}});
  auto fcl = std::make_shared<FclChecker>(baxter, scene);
  ProxyParams params;
  params.train.kernel.gamma = 10;
  params.train.beta = 100;
  params.activeLearning.maxSamples = 300;
  ProxyCollisionDetector proxy(fcl, baxter.limits(), params);
  proxy.initialize(1500);
  std::atomic<int> steps{0};
  proxy.startBackground([&](const StepReport&) { ++steps; });
  // The scene is replaced every millisecond while the updates run, but moves only in the first 20
  // replacements: how far the box goes must not depend on how long an update takes (under
  // ThreadSanitizer a step takes ten times longer, and a box that kept moving made this model's
  // accuracy a matter of timing: 0.818 in one run).
  for (int replaced = 0; steps < 5; ++replaced) {
    if (replaced < 20) scene.step();
    fcl->setScene(scene);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  proxy.stopBackground();
  proxy.step();  // one synchronous step on the final scene
  Rng rng(2);
  const Configurations test = uniformConfigurations(baxter.limits(), 1000, rng);
  const Labels truth = labelConfigurations(*fcl, test);
  const Eigen::VectorXd scores = proxy.model()->scoreBatch(test);
  std::size_t correct = 0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    correct += (scores[static_cast<Eigen::Index>(i)] > 0) == (truth[i] > 0);
  EXPECT_GT(static_cast<double>(correct) / static_cast<double>(truth.size()), 0.85);
}

// The task-space default, updates from zero weights, in the background beside a reader of the
// published models while the boxes move: the concurrency of that path, under ThreadSanitizer too
// (its statistical comparison with the warm start is in learning_quality_test.cpp).
TEST(FclOracle, UpdatesFromZeroWeightsRunBesideQueries) {
  const Robot baxter = loadRobot("baxter");
  Scene scene = loadScene(dataDirectory() / "scenes" / "baxter_three_boxes.yaml");
  auto fcl = std::make_shared<FclChecker>(baxter, scene);
  ProxyParams params = defaultProxyParams(FeatureKind::Kinematic);
  ASSERT_TRUE(params.coldStart);
  params.activeLearning.maxSamples = 500;  // the default's 2500 are slow under the sanitizers
  params.calibrationSamples = 200;
  ProxyCollisionDetector proxy(fcl, robotFeatures(baxter, FeatureKind::Kinematic), params);
  proxy.initialize(1500);
  std::atomic<int> steps{0};
  std::atomic<bool> done{false};
  std::size_t reads = 0;
  std::jthread reader([&] {
    Rng rng(3);
    const Configurations q = uniformConfigurations(baxter.limits(), 64, rng);
    while (!done) {
      const auto model = proxy.model();
      for (Eigen::Index i = 0; i < q.rows(); ++i)
        ASSERT_TRUE(std::isfinite(model->score(q.row(i).data())));
      ++reads;
    }
  });
  proxy.startBackground([&](const StepReport&) { ++steps; });
  for (int replaced = 0; steps < 3; ++replaced) {  // as in ProxyLearnsFromFclWhileTheBoxMoves
    if (replaced < 20) scene.step();
    fcl->setScene(scene);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  proxy.stopBackground();
  done = true;
  reader.join();
  EXPECT_GT(reads, 0u);
  const StepReport report = proxy.step();  // synchronous, on the final scene
  // From zero weights every support point took at least one weight update.
  EXPECT_GE(report.update.iterations, report.update.supportCount);
  Rng rng(4);
  const Configurations test = uniformConfigurations(baxter.limits(), 1000, rng);
  const ConfusionCounts counts = evaluate(*proxy.model(), test, labelConfigurations(*fcl, test));
  EXPECT_GT(counts.accuracy(), 0.9) << "TPR " << counts.tpr();
}

TEST(FclOracle, TaskSpaceDefaultsUpdateFromZeroWeightsWithMoreSamples) {
  const ProxyParams fk = defaultProxyParams(FeatureKind::Kinematic);
  EXPECT_TRUE(fk.coldStart);
  EXPECT_EQ(fk.activeLearning.maxSamples, 2500u);
  EXPECT_EQ(fk.activeLearning.exploitationShare, 0.2);
  EXPECT_EQ(fk.train.beta, defaultTrainParams(FeatureKind::Kinematic).beta);
  const ProxyParams joints = defaultProxyParams(FeatureKind::JointScaling);
  EXPECT_FALSE(joints.coldStart);  // the paper's pipeline
  EXPECT_EQ(joints.activeLearning.maxSamples, 500u);
  EXPECT_EQ(joints.activeLearning.exploitationShare, 1.0);
}

}  // namespace
}  // namespace fastron
