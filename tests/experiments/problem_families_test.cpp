// Problem families generated for any robot (fastron problems): ends free and not a turn apart on
// a joint of two turns.

#include "fastron/experiments/problem_families.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>

#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/robot_library.h"

namespace fastron::experiments {
namespace {

// A UR3's goals are drawn anywhere in its joints' +-2 pi; each joint of more than a turn then takes
// the value nearest the start of those a turn apart within its limits (the same pose), so no
// problem asks a planner to wind a joint a whole turn it need not.
TEST(ProblemFamilies, AGoalIsNotATurnAwayFromItsStartOnAJointOfTwoTurns) {
  const Robot ur3 = loadRobot("ur3");
  const std::vector<GeneratedProblem> problems =
      generateProblems(ur3, {.family = ProblemFamily::Cage, .count = 3, .seed = 7});
  ASSERT_EQ(problems.size(), 3u);
  const JointLimits limits = ur3.limits();
  std::size_t turnJoints = 0;
  for (const GeneratedProblem& problem : problems) {
    const FclChecker fcl(ur3, problem.scene, {.selfCollision = true});
    EXPECT_FALSE(fcl.inCollision(std::span<const double>(problem.start)));
    EXPECT_FALSE(fcl.inCollision(std::span<const double>(problem.goal)));
    for (std::size_t i = 0; i < ur3.dof(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      if (limits.upper()[k] - limits.lower()[k] <= 2 * std::numbers::pi) continue;
      ++turnJoints;
      const double apart = std::abs(problem.goal[i] - problem.start[i]);
      for (const double turn : {-2 * std::numbers::pi, 2 * std::numbers::pi}) {
        const double other = problem.goal[i] + turn;
        if (other < limits.lower()[k] || other > limits.upper()[k]) continue;
        EXPECT_LE(apart, std::abs(other - problem.start[i]))
            << "joint " << ur3.actuatedJointNames()[i] << " of a problem's goal";
      }
    }
  }
  EXPECT_EQ(turnJoints, 3u * 5u);  // five of the UR3's six joints turn +-2 pi
}

}  // namespace
}  // namespace fastron::experiments
