// Problem families generated for any robot (fastron problems): ends free and not a turn apart on
// a joint of two turns.

#include "fastron/experiments/problem_families.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>

#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/planning/planner.h"

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

// Start and goal free do not make a problem solvable: the gripper arm's fifth cage problem of
// seed 7 goes unsolved by every method in 30 s. With solvableWithin, the problems before it are
// the same, it is drawn anew, and every problem kept has a path on FCL.
TEST(ProblemFamilies, SolvableFamiliesKeepOnlyProblemsWithAPath) {
  const Robot arm = loadRobot("gripper-arm");
  const ProblemOptions drawn{.family = ProblemFamily::Cage, .count = 5, .seed = 7};
  ProblemOptions solvable = drawn;
  solvable.solvableWithin = 1;
  const std::vector<GeneratedProblem> free = generateProblems(arm, drawn);
  const std::vector<GeneratedProblem> kept = generateProblems(arm, solvable);
  ASSERT_EQ(kept.size(), 5u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(kept[i].start, free[i].start) << "problem " << i + 1;
    EXPECT_EQ(kept[i].goal, free[i].goal) << "problem " << i + 1;
  }
  EXPECT_NE(kept[4].goal, free[4].goal);
  const auto asVector = [](const std::vector<double>& v) {
    return Eigen::VectorXd(
        Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
  };
  const PlannerOptions options{.timeLimit = 2, .simplifyTime = 0};
  const auto plansOnFcl = [&](const GeneratedProblem& problem) {
    seedPlanners(11, 0);
    const auto fcl =
        std::make_shared<FclChecker>(arm, problem.scene, CheckerOptions{.selfCollision = true});
    return planMotion(fcl, arm.limits(), asVector(problem.start), asVector(problem.goal), options)
        .solved();
  };
  for (const GeneratedProblem& problem : kept) EXPECT_TRUE(plansOnFcl(problem));
  EXPECT_FALSE(plansOnFcl(free[4])) << "the problem drawn anew had no path";

  ProblemOptions negative = drawn;
  negative.solvableWithin = -1;
  EXPECT_THROW(generateProblems(arm, negative), InvalidArgument);
}

}  // namespace
}  // namespace fastron::experiments
