// Exact checkers called from many threads while the scene is replaced (runs under ThreadSanitizer
// in ./dev.sh test): every check answers for one whole scene, old or new.

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/robot_library.h"

namespace fastron {
namespace {

Scene ballAt(double y) {
  Scene scene;
  scene.add({"ball", Sphere{0.1}, makePose({0.3, y, 0}), std::nullopt});
  return scene;
}

template <class Checker>
void checkWhileTheSceneChanges() {
  const Robot rod = loadRobot("rod2");
  // The ball sits either on the rod at q = (0, 0) or far away: each answer belongs to one scene.
  Checker checker(rod, ballAt(0));
  const std::vector<double> q{0, 0};
  std::atomic<bool> done{false};
  std::atomic<std::size_t> hits{0}, misses{0};
  auto worker = [&] {
    while (!done) (checker.inCollision(q) ? hits : misses)++;
  };
  {
    std::jthread a(worker), b(worker);
    // Swap scenes until the workers have checked a good number of times during the swaps.
    for (int i = 0; i < 200 || hits + misses < 2000; ++i)
      checker.setScene(ballAt(i % 2 == 0 ? 2.0 : 0.0));
    done = true;
  }
  // What each check saw depends on the scheduler; the race-freedom is ThreadSanitizer's to
  // judge (./dev.sh test), the final answer below the test's.
  checker.setScene(ballAt(2.0));
  EXPECT_FALSE(checker.inCollision(q));
}

TEST(CheckerConcurrency, FclChecksDuringSceneUpdates) {
  checkWhileTheSceneChanges<FclChecker>();
}
TEST(CheckerConcurrency, GjkChecksDuringSceneUpdates) {
  checkWhileTheSceneChanges<GjkChecker>();
}

/// A camera's cloud of a few points about (x, 0, 0.4), each a ball of 2 cm.
Scene cloudAt(double x) {
  auto points = std::make_shared<CloudPoints>();
  for (int i = 0; i < 50; ++i) points->points.emplace_back(x + 0.002 * i, 0.001 * i, 0.4);
  Scene scene;
  scene.add({"camera", PointCloud{points, 0.02}, Eigen::Isometry3d::Identity(), std::nullopt});
  return scene;
}

// A new cloud each frame while two threads check and measure distances (the mesh links' distances
// build the cloud's point hierarchy on first use, from whichever thread asks first).
TEST(CheckerConcurrency, FclChecksDuringCloudUpdates) {
  const Robot panda = loadRobot("panda-mesh");
  FclChecker checker(panda, cloudAt(0.3));
  const std::vector<double> q(panda.dof(), 0.0);
  std::atomic<bool> done{false};
  std::atomic<std::size_t> asked{0};
  auto worker = [&] {
    while (!done) {
      (void)checker.inCollision(q);
      EXPECT_GE(checker.distance(q), 0.0);
      ++asked;
    }
  };
  {
    std::jthread a(worker), b(worker);
    for (int i = 0; i < 50 || asked < 100; ++i) checker.setScene(cloudAt(i % 2 == 0 ? 3.0 : 0.3));
    done = true;
  }
  checker.setScene(cloudAt(3.0));  // beyond the arm's reach: cropped away
  EXPECT_FALSE(checker.inCollision(q));
}

// The mesh Panda's self-pair tables, their pairs built on every core at once (coarse: 5 cm of
// slack), are the same tables each time: each pair's distances come from one thread's kinematics.
// A checker given them answers from several threads.
TEST(CheckerConcurrency, SelfPairTablesBuiltOnEveryCore) {
  const Robot panda = loadRobot("panda-mesh");
  const CheckerOptions options{.selfCollision = true, .selfPairSlack = 0.05};
  const FclChecker first(panda, Scene{}, options), second(panda, Scene{}, options);
  ASSERT_GE(first.selfPairTableCount(), 2U);
  ASSERT_EQ(first.selfPairTableCount(), second.selfPairTableCount());
  for (std::size_t t = 0; t < first.selfPairTableCount(); ++t) {
    EXPECT_EQ((*first.selfPairTables())[t].distance, (*second.selfPairTables())[t].distance);
  }
  const FclChecker given(panda, ballAt(0),
                         {.selfCollision = true, .selfPairTables = first.selfPairTables()});
  const std::vector<double> q(panda.dof(), 0.0);
  const bool expected = given.inCollision(q);
  std::atomic<std::size_t> differ{0};
  {
    auto worker = [&] {
      for (int i = 0; i < 200; ++i) differ += given.inCollision(q) != expected ? 1 : 0;
    };
    std::jthread a(worker), b(worker);
  }
  EXPECT_EQ(differ, 0U);
}

}  // namespace
}  // namespace fastron
