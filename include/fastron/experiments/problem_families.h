#pragma once
// Planning problems generated in MotionBenchMaker's file format (a MoveIt scene and request per
// problem, scene_file.h and moveit_request.h): the robot reaches into a cage, or into an open box,
// whose pose varies from problem to problem, as that benchmark's `cage` and `box` families do. The
// geometry is this project's own, after the shapes of those families; start and goal are found by
// sampling, not by inverse kinematics, so the problems are of the benchmark's kind but not its
// problems.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/geometry/robot.h"
#include "fastron/geometry/scene.h"

namespace fastron::experiments {

enum class ProblemFamily { Cage, Box };
std::string_view toString(ProblemFamily family);
/// "cage" or "box"; throws InvalidArgument naming the value and the choices.
ProblemFamily parseProblemFamily(std::string_view name);

struct ProblemOptions {
  ProblemFamily family = ProblemFamily::Cage;
  std::size_t count = 10;
  std::uint64_t seed = 1;
  /// Start and goal are also free of the robot's collisions with itself (its allowed pairs
  /// skipped), as MoveIt requires.
  bool selfCollision = true;
  /// The link whose origin must reach the target (empty: of the child of the last actuated joint
  /// and the links fixed to it, the one farthest from it, e.g. the Panda's grasp target).
  std::string tipLink;
  /// The goal puts the tip link's origin within this distance (m) of the target: a point 0.12 m
  /// above the object inside the structure.
  double reach = 0.12;
  /// Uniform configurations drawn per attempt at a goal or a start before the structure is placed
  /// anew (at most 20 placements per problem).
  std::size_t samplesPerAttempt = 200000;
  /// When positive, a problem is kept only when RRT-Connect on FCL (planMotion's defaults, the
  /// same self-collision setting, its planners seeded from `seed` and the problem's number) finds
  /// a path within this many seconds; otherwise the structure is placed anew. Start and goal free
  /// do not make a problem solvable: two of ten gripper-arm cage problems of seed 7 went unsolved
  /// by every method in 5 s (by FCL in 30 s with two planner seeds), and each costs a benchmark
  /// its whole time limit per method. 0: no plan (the families of earlier runs, unchanged). A plan
  /// that ends near the limit can make two runs keep different problems.
  double solvableWithin = 0;
};

/// Takes `goal`'s value of each revolute joint of more than a turn (a UR arm's +-2 pi), among
/// those a whole turn apart within its limits, nearest `start`'s, when every link of `robot` stays
/// where it is (a joint that a mimic follows at another ratio keeps its value): the same pose, the
/// same answer from every checker. Goals drawn anywhere in +-2 pi are otherwise a turn away from
/// the start on some joint as often as not, and a turn can be closed to every planner (the arm
/// would sweep through the table or itself): of ten UR3 cage problems drawn so, four went
/// unsolved by every method in 5 s (docs/log/2026-12-01-an-arms-collisions-with-itself.md).
/// `start` and `goal` hold robot.dof() values.
void takeTurnsNearestStart(const Robot& robot, std::span<const double> start,
                           std::span<double> goal);

/// One problem: obstacles, and start and goal over the robot's actuated joints, both free under
/// FCL (with self-collision when asked); the start puts the tip in front of the robot, outside the
/// structure, the goal near the object inside it. A revolute joint of more than a turn (a UR arm's
/// +-2 pi) has the goal's value, of those a whole turn apart within its limits that leave every
/// link where it is, nearest the start's.
struct GeneratedProblem {
  Scene scene;
  std::vector<double> start, goal;
};

/// `options.count` problems, the same for the same robot and options. The structure is placed
/// 0.45-1.15 m in front of the robot's base (+x) as MotionBenchMaker places it for the Panda: the
/// cage's floor 0.26 m above the base, the box's 0.58 m below it. A robot that finds no start and
/// goal there for the first problem (another height, a mobile base, a torso) gets the structure
/// raised or lowered instead, by the lifts that bring the most of its tip's places at uniform
/// configurations near the object first (a few placements each), and keeps the first that works
/// for every problem; the start region is raised with it. Throws InvalidArgument for bad options
/// or an unknown tip link, and Error when no start or goal is found (a robot that cannot reach
/// into the structure).
std::vector<GeneratedProblem> generateProblems(const Robot& robot, const ProblemOptions& options);

/// Writes each problem as sceneNNNN.yaml and requestNNNN.yaml (NNNN from 0001) into `folder`,
/// which is created; the request names the robot's actuated joints, in group `group`. Throws
/// FileError naming a file that cannot be written.
void writeProblems(const std::filesystem::path& folder, const Robot& robot,
                   const std::vector<GeneratedProblem>& problems, const std::string& group);

}  // namespace fastron::experiments
