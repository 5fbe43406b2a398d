// The seam of the exact checkers: every backend the factory names, used through SceneChecker
// alone, as the commands, the pipeline and Python use them.

#include "fastron/geometry/scene_checkers.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/robot_library.h"
#include "temp_dir.h"

namespace fastron {
namespace {

using ::testing::HasSubstr;

Scene boxAndBall() {
  Scene scene;
  scene.add({"box", Box{Eigen::Vector3d(0.2, 0.2, 0.2)},
             makePose({0.6, -0.6, 0.2}, {0.3, 0.2, 0.5}), std::nullopt});
  scene.add({"ball", Sphere{0.12}, makePose({0.4, -0.9, 0.5}), std::nullopt});
  return scene;
}

TEST(SceneCheckers, EveryBackendIsBuiltByItsName) {
  const std::vector<SceneCheckerKind> kinds = sceneCheckerKinds();
  ASSERT_GE(kinds.size(), 2u);
  EXPECT_EQ(kinds.front().name, kDefaultSceneChecker);
  const Robot baxter = loadRobot("baxter");
  for (const SceneCheckerKind& kind : kinds) {
    SCOPED_TRACE(kind.name);
    EXPECT_FALSE(kind.description.empty());
    const auto checker =
        makeSceneChecker(kind.name, baxter, boxAndBall(), {.selfCollision = true, .padding = 0.01});
    EXPECT_EQ(checker->robot().name(), baxter.name());
    EXPECT_EQ(checker->dof(), 7u);
    EXPECT_TRUE(checker->options().selfCollision);
    EXPECT_DOUBLE_EQ(checker->options().padding, 0.01);
  }
  EXPECT_EQ(makeSceneChecker("fcl", baxter, Scene{})->name(), "FCL");
  EXPECT_EQ(makeSceneChecker("gjk", baxter, Scene{})->name(), "GJK");
}

TEST(SceneCheckers, AnUnknownNameIsRefusedWithTheKnownOnes) {
  const std::string message = test::messageOf<InvalidArgument>(
      [] { (void)makeSceneChecker("bullet", loadRobot("rod2"), Scene{}); });
  EXPECT_THAT(message, HasSubstr("unknown checker 'bullet'"));
  EXPECT_THAT(message, HasSubstr("fcl, gjk"));
}

// A contact found whenever the configuration collides and only then, naming a link of the robot
// and an obstacle of the scene (or two links for a self-collision that no matrix allows).
TEST(SceneCheckers, EveryBackendNamesWhatCollided) {
  const Robot baxter = loadRobot("baxter");
  const AllowedCollisionMatrix adjacent = baxter.adjacentLinks();
  Rng rng(3);
  const Configurations q = uniformConfigurations(baxter.limits(), 400, rng);
  for (const SceneCheckerKind& kind : sceneCheckerKinds()) {
    SCOPED_TRACE(kind.name);
    const auto checker = makeSceneChecker(kind.name, baxter, boxAndBall(), {.selfCollision = true});
    std::size_t obstacleHits = 0, selfHits = 0;
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      const std::span<const double> c(q.row(i).data(), 7);
      const auto contact = checker->firstContact(c);
      ASSERT_EQ(contact.has_value(), checker->inCollision(c)) << "row " << i;
      if (!contact) continue;
      EXPECT_GE(baxter.linkIndex(contact->robotLink), 0);
      if (contact->selfCollision) {
        ++selfHits;
        EXPECT_GE(baxter.linkIndex(contact->other), 0);
        EXPECT_FALSE(adjacent.allowed(contact->robotLink, contact->other));
      } else {
        ++obstacleHits;
        EXPECT_THAT(contact->other, ::testing::AnyOf("box", "ball"));
      }
    }
    EXPECT_GT(obstacleHits, 5u);
    EXPECT_GT(selfHits, 5u);
  }
}

TEST(SceneCheckers, SetSceneThroughTheSeamMovesTheObstacles) {
  const Robot rod = loadRobot("rod2");  // capsule from x = 0 to 0.5, radius 0.03, at q = 0
  Scene scene;
  scene.add({"ball", Sphere{0.1}, makePose({2, 0, 0}), std::nullopt});
  const std::vector<double> q{0, 0};
  for (const SceneCheckerKind& kind : sceneCheckerKinds()) {
    SCOPED_TRACE(kind.name);
    const auto checker = makeSceneChecker(kind.name, rod, scene);
    EXPECT_FALSE(checker->firstContact(q).has_value());
    Scene moved = scene;
    moved.setPose("ball", makePose({0.3, 0, 0}));
    checker->setScene(moved);
    ASSERT_TRUE(checker->firstContact(q).has_value());
    EXPECT_EQ(checker->firstContact(q)->other, "ball");
  }
}

TEST(SceneCheckers, DistanceWhereTheBackendMeasuresIt) {
  const Robot rod = loadRobot("rod2");
  Scene scene;
  scene.add({"ball", Sphere{0.1}, makePose({0.8, 0, 0}), std::nullopt});
  const std::vector<double> q{0, 0};
  for (const SceneCheckerKind& kind : sceneCheckerKinds()) {
    SCOPED_TRACE(kind.name);
    const auto checker = makeSceneChecker(kind.name, rod, scene);
    EXPECT_THROW((void)checker->distance(std::vector<double>{0}), InvalidArgument);
    EXPECT_THROW((void)checker->firstContact(std::vector<double>{0, std::nan("")}),
                 InvalidArgument);
    if (checker->measuresDistance()) {
      EXPECT_NEAR(checker->distance(q), 0.8 - 0.1 - 0.53, 1e-4);
    } else {
      EXPECT_THAT(test::messageOf<Unsupported>([&] { (void)checker->distance(q); }),
                  HasSubstr(checker->name() + " does not measure distances"));
    }
  }
  EXPECT_TRUE(makeSceneChecker("fcl", rod, scene)->measuresDistance());
  EXPECT_FALSE(makeSceneChecker("gjk", rod, scene)->measuresDistance());
}

}  // namespace
}  // namespace fastron
