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
// seed 7 goes unsolved by FCL in 30 s with most planner seeds. With solvableWithin, every problem
// kept has a path: planned again with the generator's planner seed (the seed and the problem's
// number), RRT-Connect on FCL repeats the search that found it, with time to spare for a slow
// (sanitized) build.
TEST(ProblemFamilies, SolvableFamiliesKeepOnlyProblemsWithAPath) {
  const Robot arm = loadRobot("gripper-arm");
  ProblemOptions solvable;
  solvable.family = ProblemFamily::Cage;
  solvable.count = 5;
  solvable.seed = 7;
  solvable.solvableWithin = 1;
  const std::vector<GeneratedProblem> kept = generateProblems(arm, solvable);
  ASSERT_EQ(kept.size(), 5u);
  const auto dim = static_cast<Eigen::Index>(arm.dof());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    seedPlanners(solvable.seed, i);
    const auto fcl =
        std::make_shared<FclChecker>(arm, kept[i].scene, CheckerOptions{.selfCollision = true});
    PlannerOptions options;
    options.timeLimit = 30;
    options.simplifyTime = 0;
    EXPECT_TRUE(planMotion(fcl, arm.limits(),
                           Eigen::Map<const Eigen::VectorXd>(kept[i].start.data(), dim),
                           Eigen::Map<const Eigen::VectorXd>(kept[i].goal.data(), dim), options)
                    .solved())
        << "problem " << i + 1;
  }
  ProblemOptions negative = solvable;
  negative.solvableWithin = -1;
  EXPECT_THROW(generateProblems(arm, negative), InvalidArgument);
}

}  // namespace
}  // namespace fastron::experiments
