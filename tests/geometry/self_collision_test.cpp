// The self-collision survey: per-pair collision shares against their closed form, Setup
// Assistant's verdicts, and the shipped robots' home configurations.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/self_collision_survey.h"

namespace fastron {
namespace {

Joint revoluteZ(const std::string& name, int parent, int child) {
  Joint j;
  j.name = name;
  j.type = JointType::Revolute;
  j.parent = parent;
  j.child = child;
  j.lower = -std::numbers::pi;
  j.upper = std::numbers::pi;
  return j;
}

// Three joints about the same vertical axis. The base holds a 0.1 m ball 0.5 m out along x;
// `behind` (after two joints) holds one 0.5 m out the other way, `ahead` (after three) one
// 0.5 m out along its x; the hub's ball sits high above everything. Non-adjacent pairs:
// base/behind (touch when the angle puts the balls together, not at home), base/ahead (touch at
// home) and hub/ahead (never touch).
Robot carousel() {
  const auto ball = [](int link, Eigen::Vector3d at, double r) {
    return LinkShape{link, Eigen::Isometry3d(Eigen::Translation3d(at)), Sphere{r}};
  };
  return Robot("carousel", {{"base", -1}, {"hub", -1}, {"behind", -1}, {"ahead", -1}},
               {revoluteZ("j1", 0, 1), revoluteZ("j2", 1, 2), revoluteZ("j3", 2, 3)},
               {ball(0, {0.5, 0, 0}, 0.1), ball(1, {0, 0, 0.5}, 0.01), ball(2, {-0.5, 0, 0}, 0.1),
                ball(3, {0.5, 0, 0}, 0.1)});
}

const LinkPairSurvey& pair(const SelfCollisionSurvey& s, const std::string& a,
                           const std::string& b) {
  for (const auto& p : s.pairs) {
    if ((p.linkA == a && p.linkB == b) || (p.linkA == b && p.linkB == a)) return p;
  }
  throw std::runtime_error("no pair " + a + " / " + b);
}

TEST(SelfCollisionSurvey, SharesMatchTheGeometryAndVerdictsFollowSetupAssistant) {
  const Robot robot = carousel();
  const SelfCollisionOptions options{.samples = 4000, .seed = 3};
  const SelfCollisionSurvey s = surveySelfCollisions(robot, options);
  ASSERT_EQ(s.pairs.size(), 3u);  // adjacent pairs are not surveyed

  // Two balls of 0.1 m on a 0.5 m circle touch within 2 asin(0.2) of each other; the summed
  // angle of uniform joints is uniform on the circle.
  const double share = 2 * std::asin(0.2) / std::numbers::pi;
  const auto& behind = pair(s, "base", "behind");
  const auto& ahead = pair(s, "base", "ahead");
  const auto& never = pair(s, "hub", "ahead");
  EXPECT_NEAR(static_cast<double>(behind.collisions) / 4000, share, 0.02);
  EXPECT_NEAR(static_cast<double>(ahead.collisions) / 4000, share, 0.02);
  EXPECT_EQ(never.collisions, 0u);
  EXPECT_FALSE(behind.atHome);
  EXPECT_TRUE(ahead.atHome);
  EXPECT_EQ(behind.verdict, PairVerdict::Enabled);
  EXPECT_EQ(ahead.verdict, PairVerdict::Default);
  EXPECT_EQ(never.verdict, PairVerdict::Never);

  // Only the enabled pair counts once the others are disabled: the checker agrees, sample by
  // sample, when the default pair is allowed.
  Robot allowing = robot;
  allowing.allowedCollisions().allow("base", "ahead");
  const FclChecker checker(allowing, Scene{}, {.selfCollision = true});
  Rng rng(options.seed);
  const Configurations q = uniformConfigurations(robot.limits(), options.samples, rng);
  std::size_t colliding = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    colliding += checker.inCollision({q.row(i).data(), 3});
  EXPECT_EQ(s.configurationsInCollision, colliding);
  EXPECT_EQ(s.configurationsInCollision, behind.collisions);
  EXPECT_GT(s.configurationsBefore, s.configurationsInCollision);
  EXPECT_LE(s.configurationsBefore, behind.collisions + ahead.collisions);

  // A low "always" threshold turns the sometimes-colliding pair into an always pair; being in
  // collision at home still comes first.
  const SelfCollisionSurvey low =
      surveySelfCollisions(robot, {.samples = 500, .alwaysShare = 0.05, .seed = 3});
  EXPECT_EQ(pair(low, "base", "behind").verdict, PairVerdict::Always);
  EXPECT_EQ(pair(low, "base", "ahead").verdict, PairVerdict::Default);
  EXPECT_EQ(low.configurationsInCollision, 0u);
}

TEST(SelfCollisionSurvey, AllowedPairsAreNotSurveyedAndBadOptionsAreRefused) {
  Robot robot = carousel();
  robot.allowedCollisions().allow("ahead", "base");
  const SelfCollisionSurvey s = surveySelfCollisions(robot, {.samples = 100});
  EXPECT_EQ(s.pairs.size(), 2u);
  EXPECT_EQ(s.samples, 100u);
  EXPECT_THROW(surveySelfCollisions(robot, {.samples = 0}), InvalidArgument);
  EXPECT_THROW(surveySelfCollisions(robot, {.alwaysShare = 0}), InvalidArgument);
  EXPECT_THROW(surveySelfCollisions(robot, {.alwaysShare = 1.5}), InvalidArgument);
}

// The catalogue allows every pair that touches at the home configuration, so a shipped robot at
// home is free of self-collision. Not the mesh Panda: its pairs are MoveIt's, and MoveIt too finds
// its hand on link 5 with every joint at 0 (its "ready" state is free: srdf_test.cpp).
TEST(SelfCollisionSurvey, ShippedRobotsAreFreeAtHome) {
  for (const RobotEntry& entry : shippedRobots()) {
    if (entry.name == "panda-mesh") continue;
    const SelfCollisionSurvey s = surveySelfCollisions(loadRobot(entry.name), {.samples = 50});
    for (const auto& p : s.pairs) {
      EXPECT_FALSE(p.atHome) << entry.name << ": " << p.linkA << " / " << p.linkB;
    }
  }
}

}  // namespace
}  // namespace fastron
