// Tables of a self pair's distance over the one or two coordinates that turn its shapes against
// each other: their bound never exceeds the distance and falls short of it by at most the slack,
// and the mesh Panda's certified checks with tables answer as the dense check.

#include "fastron/geometry/self_pair_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/motion_states.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene.h"

namespace fastron {
namespace {

#ifdef FASTRON_SANITIZED
constexpr std::size_t kMotions = 60;  // sanitizers slow checks down ~10 times
constexpr std::size_t kStates = 300;
#else
constexpr std::size_t kMotions = 300;
constexpr std::size_t kStates = 2000;
#endif

// A distance of coordinates 0 and 2 of three whose slopes stay within 0.1 and 0.05 per unit.
double smoothDistance(const double* q) {
  return 0.03 + 0.1 * std::sin(q[0]) + 0.05 * std::cos(q[2]);
}

TEST(SelfPairTable, BoundsNeverExceedTheDistanceAndMissItByAtMostTheSlack) {
  const JointLimits limits(Eigen::Vector3d(-2, -1, -3), Eigen::Vector3d(2, 1, 3));
  const double slack = 0.004;
  const auto table =
      tabulateSelfPair(4, 7, Eigen::Vector3d(0.1, 0, 0.05), limits, slack, 100000, smoothDistance);
  ASSERT_TRUE(table.has_value());
  EXPECT_EQ(table->axes, 2U);
  EXPECT_EQ(table->coordinate[0], 0U);
  EXPECT_EQ(table->coordinate[1], 2U);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0, 1);
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    // Within the limits and up to half a unit beyond them (a motion's state is within them; the
    // bound must hold anyway).
    Eigen::Vector3d q;
    for (int c = 0; c < 3; ++c) {
      q[c] = limits.lower()[c] - 0.5 + (limits.upper()[c] - limits.lower()[c] + 1) * unit(rng);
    }
    const double bound = table->lowerBound(q.data()), exact = smoothDistance(q.data());
    ASSERT_LE(bound, exact) << "at " << q.transpose();
    const bool inside =
        (q.array() >= limits.lower().array()).all() && (q.array() <= limits.upper().array()).all();
    if (inside) worst = std::max(worst, exact - bound);
  }
  // The levers equal the slopes' bounds: between the nearest node and q the distance may rise by
  // as much as the bound takes off, so the bound may miss by twice the slack, not more.
  EXPECT_LE(worst, 2 * slack + 1e-6);
  EXPECT_GT(worst, 0);
  const double nan[3] = {std::nan(""), 0, 0};
  EXPECT_EQ(table->lowerBound(nan), -std::numeric_limits<double>::infinity());
}

TEST(SelfPairTable, SkipsPairsItCannotTabulateAndRefusesBadInput) {
  const JointLimits limits(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1));
  const Eigen::Vector3d three(0.1, 0.1, 0.1), none(0, 0, 0), one(0, 0.2, 0);
  EXPECT_FALSE(tabulateSelfPair(0, 1, three, limits, 0.01, 100000, smoothDistance));
  EXPECT_FALSE(tabulateSelfPair(0, 1, none, limits, 0.01, 100000, smoothDistance));
  EXPECT_FALSE(tabulateSelfPair(0, 1, one, limits, 1e-6, 1000, smoothDistance));  // too many nodes
  const auto single = tabulateSelfPair(0, 1, one, limits, 0.01, 1000, smoothDistance);
  ASSERT_TRUE(single.has_value());
  EXPECT_EQ(single->axes, 1U);
  EXPECT_EQ(single->distance.size(), single->nodes[0]);
  EXPECT_THROW(tabulateSelfPair(0, 1, one, limits, 0, 1000, smoothDistance), InvalidArgument);
  EXPECT_THROW(tabulateSelfPair(0, 1, Eigen::Vector2d(0.1, 0), limits, 0.01, 1000, smoothDistance),
               InvalidArgument);
  EXPECT_THROW(
      tabulateSelfPair(0, 1, Eigen::Vector3d(-0.1, 0, 0), limits, 0.01, 1000, smoothDistance),
      InvalidArgument);
  const Robot panda = loadRobot("panda-mesh");
  EXPECT_THROW(FclChecker(panda, Scene{}, {.selfCollision = true, .selfPairSlack = -1}),
               InvalidArgument);
}

// The mesh Panda among boxes, self-collision on: with tables for its self pairs of meshes the
// certified checks of motions and of single configurations answer as FCL asked about every state.
TEST(SelfPairTable, MeshPandaChecksWithTablesAnswerAsTheDenseCheck) {
  const Robot robot = loadRobot("panda-mesh");
  Scene scene;
  scene.add(Obstacle{"shelf", Box{{0.3, 0.6, 0.04}},
                     Eigen::Isometry3d(Eigen::Translation3d(0.6, 0, 0.5))});
  scene.add(Obstacle{"post", Box{{0.06, 0.06, 0.5}},
                     Eigen::Isometry3d(Eigen::Translation3d(0.4, 0.35, 0.5))});
  const FclChecker dense(robot, scene, {.selfCollision = true, .proveMotionsFree = false});
  const FclChecker tables(robot, scene, {.selfCollision = true, .selfPairSlack = 0.02});
  ASSERT_GE(tables.selfPairTableCount(), 2U);  // link 5 against link 7 and the hand at least
  const JointLimits limits = robot.limits();
  const std::size_t dim = robot.dof();
  Rng rng(11);
  std::size_t selfColliding = 0;
  for (std::size_t i = 0; i < kStates; ++i) {
    const Eigen::VectorXd q = uniformConfigurations(limits, 1, rng).row(0).transpose();
    const std::span<const double> at(q.data(), dim);
    const bool expected = dense.inCollision(at);
    ASSERT_EQ(tables.inCollision(at), expected) << "state " << i;
    if (expected) {
      const auto contact = dense.firstContact(at);
      selfColliding += contact && contact->selfCollision;
    }
  }
  EXPECT_GT(selfColliding, 0U);  // the states met self-contact
  std::normal_distribution<double> gauss;
  std::size_t colliding = 0;
  for (std::size_t m = 0; m < kMotions; ++m) {
    const Eigen::VectorXd from = uniformConfigurations(limits, 1, rng).row(0).transpose();
    Eigen::VectorXd direction(dim);
    for (auto& v : direction) v = gauss(rng);
    const double length = std::uniform_real_distribution<double>(0.05, 1.5)(rng);
    const Eigen::VectorXd to =
        (from + length * direction.normalized()).cwiseMax(limits.lower()).cwiseMin(limits.upper());
    const std::size_t n = segmentCount(from.data(), to.data(), dim, 0.03);
    std::vector<double> states;
    motionStates(from.data(), to.data(), dim, n, states);
    const bool denseHit = dense.firstInCollision(states.data(), n) < n;
    ASSERT_EQ(tables.motionCollision(from.data(), to.data(), n).collidingState != 0, denseHit)
        << "motion " << m << " of " << n << " segments";
    colliding += denseHit;
  }
  EXPECT_GT(colliding, 0U);
  EXPECT_LT(colliding, kMotions);
  std::cout << "mesh Panda with " << tables.selfPairTableCount()
            << " self-pair tables: " << selfColliding << " of " << kStates
            << " states in self-contact, " << colliding << " of " << kMotions
            << " motions colliding\n";
}

}  // namespace
}  // namespace fastron
