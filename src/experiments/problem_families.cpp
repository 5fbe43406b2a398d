#include "fastron/experiments/problem_families.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <span>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/moveit_writer.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {
namespace {

struct Panel {
  const char* name;
  Eigen::Vector3d size, centre;
  double pitch = 0;  // about y, for the box's slanted lid
};

// The panels in the frame of MotionBenchMaker's scene descriptions: a 0.7 m square base plate
// centred 0.8 m ahead, walls 0.7 m high, the robot's side open (-x). `structureOrigin` is where
// that frame lies relative to the robot, as the benchmark offsets it for the Panda: the cage's
// floor above the robot's base, the box's well below it, reached from above.
std::vector<Panel> panels(ProblemFamily family) {
  const Eigen::Vector3d plate(0.7, 0.7, 0.04), side(0.7, 0.04, 0.7), back(0.04, 0.7, 0.7);
  std::vector<Panel> p{{"base", plate, {0.8, 0, 0.44}},
                       {"side_left", side, {0.8, -0.35, 0.8}},
                       {"side_right", side, {0.8, 0.35, 0.8}},
                       {"side_back", back, {1.15, 0, 0.8}}};
  if (family == ProblemFamily::Cage) {
    // Open at the front but for two bars, closed on top.
    p.push_back({"side_front_low", {0.04, 0.7, 0.04}, {0.45, 0, 0.6}});
    p.push_back({"side_front_high", {0.04, 0.7, 0.04}, {0.45, 0, 0.9}});
    p.push_back({"side_cap", {0.65, 0.65, 0.04}, {0.85, 0, 1.15}});
  } else {
    // A front wall up to 0.95 m and a lid slanted up towards the robot: the opening is above the
    // front wall, under the lid.
    p.push_back({"side_front", {0.04, 0.7, 0.5}, {0.45, 0, 0.7}});
    p.push_back({"side_cap", {0.7, 0.7, 0.04}, {0.9, 0, 1.3}, 0.6});
  }
  return p;
}

Eigen::Vector3d structureOrigin(ProblemFamily family) {
  return family == ProblemFamily::Cage ? Eigen::Vector3d(0, 0, -0.18)
                                       : Eigen::Vector3d(-0.15, 0, -1.02);
}

// The object's place on the base plate before any variation: the target the structure is lifted
// to bring within a robot's reach.
Eigen::Vector3d nominalTarget(ProblemFamily family) {
  const double above = family == ProblemFamily::Cage ? 0.035 : 0.07;
  return structureOrigin(family) + Eigen::Vector3d(0.8, 0, 0.46 + above + 0.12);
}

// The whole structure turned about the robot's z axis and shifted, as MotionBenchMaker varies its
// scenes, with the object at a random place on the base plate; all of it raised by `lift`.
Scene placeStructure(ProblemFamily family, Rng& rng, double lift, Eigen::Vector3d& target) {
  std::uniform_real_distribution<double> unit(-1, 1);
  const double yaw = 0.35 * unit(rng);
  const Eigen::Vector3d shift(0.08 * unit(rng), 0.12 * unit(rng), 0.05 * unit(rng) + lift);
  const Eigen::Isometry3d place =
      makePose(Eigen::Vector3d::Zero(), {0, 0, yaw}) * makePose(structureOrigin(family) + shift);
  Scene scene;
  for (const Panel& panel : panels(family)) {
    scene.add({panel.name, Box{panel.size}, place * makePose(panel.centre, {0, panel.pitch, 0}),
               std::nullopt});
  }
  const Eigen::Vector3d onPlate(0.8 + 0.2 * unit(rng), 0.2 * unit(rng), 0.46);
  Eigen::Vector3d objectCentre;
  if (family == ProblemFamily::Cage) {
    objectCentre = onPlate + Eigen::Vector3d(0, 0, 0.035);
    scene.add({"Cube1", Box{Eigen::Vector3d::Constant(0.07)}, place * makePose(objectCentre),
               std::nullopt});
  } else {
    objectCentre = onPlate + Eigen::Vector3d(0, 0, 0.07);
    scene.add({"Can1", Cylinder{0.03, 0.14}, place * makePose(objectCentre), std::nullopt});
  }
  target = place * (objectCentre + Eigen::Vector3d(0, 0, 0.12));
  return scene;
}

// A configuration drawn uniformly, free under `checker`, whose tip lies where `wanted` says;
// false when none is among `samples` draws.
template <class Wanted>
bool findConfiguration(const Robot& robot, int tip, const CollisionChecker& checker,
                       std::size_t samples, Rng& rng, const Wanted& wanted,
                       std::vector<double>& found) {
  KinematicsData kinematics = makeKinematicsData(robot);
  constexpr std::size_t kBatch = 4096;
  for (std::size_t drawn = 0; drawn < samples; drawn += kBatch) {
    const Configurations q = uniformConfigurations(robot.limits(), kBatch, rng);
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      forwardKinematics(robot, q.row(i).data(), kinematics);
      if (!wanted(kinematics.linkPoses[static_cast<std::size_t>(tip)].translation())) continue;
      const std::span<const double> c(q.row(i).data(), robot.dof());
      if (checker.inCollision(c)) continue;
      found.assign(c.begin(), c.end());
      return true;
    }
  }
  return false;
}

// Lifts of the structure (m) for a robot that cannot reach into it where MotionBenchMaker puts it
// for the Panda: those that bring the most of the tip's places (at uniform configurations) within
// `reach` of the nominal target first. A lift of 0 keeps the benchmark's own layout.
std::vector<double> liftsByReach(const Robot& robot, int tip, ProblemFamily family, double reach) {
  constexpr double kStep = 0.05, kMost = 2.0;
  constexpr std::size_t kSamples = 20000;
  Rng rng(7);
  const Configurations q = uniformConfigurations(robot.limits(), kSamples, rng);
  KinematicsData kinematics = makeKinematicsData(robot);
  const Eigen::Vector3d target = nominalTarget(family);
  std::vector<std::pair<std::size_t, double>> scored;  // (tips within reach, lift)
  std::vector<Eigen::Vector3d> tips;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    forwardKinematics(robot, q.row(i).data(), kinematics);
    tips.push_back(kinematics.linkPoses[static_cast<std::size_t>(tip)].translation());
  }
  for (double lift = -kMost; lift <= kMost + 1e-9; lift += kStep) {
    const Eigen::Vector3d at = target + Eigen::Vector3d(0, 0, lift);
    const auto near = static_cast<std::size_t>(
        std::count_if(tips.begin(), tips.end(),
                      [&](const Eigen::Vector3d& p) { return (p - at).norm() <= reach; }));
    if (near > 0) scored.emplace_back(near, lift);
  }
  std::stable_sort(scored.begin(), scored.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<double> lifts;
  for (const auto& [near, lift] : scored) lifts.push_back(lift);
  return lifts;
}

// Of the child of the last actuated joint and the links fixed to it, the one farthest from it: the
// Panda's grasp target between its fingertips, beyond its flange and hand.
int defaultTip(const Robot& robot) {
  const int child = robot.joints()[static_cast<std::size_t>(robot.actuatedJoints().back())].child;
  const KinematicsData kinematics = kinematicsAtZero(robot);
  const auto& poses = kinematics.linkPoses;
  std::vector<std::uint8_t> onTip(robot.links().size(), 0);
  onTip[static_cast<std::size_t>(child)] = 1;
  int tip = child;
  double farthest = 0;
  for (const Joint& joint : robot.joints()) {  // parent before child
    if (joint.type != JointType::Fixed || onTip[static_cast<std::size_t>(joint.parent)] == 0) {
      continue;
    }
    onTip[static_cast<std::size_t>(joint.child)] = 1;
    const double distance = (poses[static_cast<std::size_t>(joint.child)].translation() -
                             poses[static_cast<std::size_t>(child)].translation())
                                .norm();
    if (distance > farthest) {
      farthest = distance;
      tip = joint.child;
    }
  }
  return tip;
}

}  // namespace

void takeTurnsNearestStart(const Robot& robot, std::span<const double> start,
                           std::span<double> goal) {
  if (start.size() != robot.dof() || goal.size() != robot.dof()) {
    throw InvalidArgument("takeTurnsNearestStart: start and goal need " +
                          std::to_string(robot.dof()) + " values, got " +
                          std::to_string(start.size()) + " and " + std::to_string(goal.size()));
  }
  constexpr double kTurn = 2 * std::numbers::pi;
  const JointLimits limits = robot.limits();
  KinematicsData kinematics = makeKinematicsData(robot);
  forwardKinematics(robot, goal.data(), kinematics);
  const auto poses = kinematics.linkPoses;  // where the drawn goal puts the links
  for (const std::size_t i : coordinatesOfMoreThanATurn(robot)) {
    const auto k = static_cast<Eigen::Index>(i);
    const double nearest = start[i] + std::remainder(goal[i] - start[i], kTurn);
    double best = goal[i];
    for (const double value : {nearest, nearest - kTurn, nearest + kTurn}) {
      if (value >= limits.lower()[k] && value <= limits.upper()[k] &&
          std::abs(value - start[i]) < std::abs(best - start[i]))
        best = value;
    }
    const double drawn = goal[i];
    goal[i] = best;
    forwardKinematics(robot, goal.data(), kinematics);
    for (std::size_t link = 0; link < poses.size(); ++link) {
      if (!kinematics.linkPoses[link].isApprox(poses[link], 1e-9)) {
        goal[i] = drawn;
        break;
      }
    }
  }
}

std::string_view toString(ProblemFamily family) {
  return family == ProblemFamily::Cage ? "cage" : "box";
}

ProblemFamily parseProblemFamily(std::string_view name) {
  if (name == "cage") return ProblemFamily::Cage;
  if (name == "box") return ProblemFamily::Box;
  throw InvalidArgument("unknown problem family '" + std::string(name) + "' (cage, box)");
}

std::vector<GeneratedProblem> generateProblems(const Robot& robot, const ProblemOptions& options) {
  if (options.count == 0) throw InvalidArgument("problem count must be at least 1");
  if (!(options.reach > 0) || !std::isfinite(options.reach)) {
    throw InvalidArgument("reach must be a positive distance, got " +
                          std::to_string(options.reach));
  }
  if (options.samplesPerAttempt == 0) throw InvalidArgument("samplesPerAttempt must be positive");
  if (!(options.solvableWithin >= 0) || !std::isfinite(options.solvableWithin)) {
    throw InvalidArgument("solvableWithin must be a non-negative number of seconds, got " +
                          std::to_string(options.solvableWithin));
  }
  const int tip = options.tipLink.empty() ? defaultTip(robot) : robot.linkIndex(options.tipLink);
  Rng rng(options.seed);
  std::vector<GeneratedProblem> problems;
  constexpr int kPlacements = 20;
  // The benchmark's layout (lift 0) unless the first problem finds no start and goal there; then
  // the lifts that bring the structure within the robot's reach, best first, a few placements each.
  std::vector<double> lifts{0.0};
  constexpr std::size_t kLiftsTried = 6;
  constexpr int kPlacementsPerLift = 4;
  // Whether RRT-Connect on `exact` finds a path for the problem within options.solvableWithin.
  const auto hasPath = [&](const std::shared_ptr<const SceneChecker>& exact,
                           const GeneratedProblem& problem) {
    seedPlanners(options.seed, problems.size());
    const auto dim = static_cast<Eigen::Index>(robot.dof());
    return planMotion(exact, robot.limits(),
                      Eigen::Map<const Eigen::VectorXd>(problem.start.data(), dim),
                      Eigen::Map<const Eigen::VectorXd>(problem.goal.data(), dim),
                      {.timeLimit = options.solvableWithin, .simplifyTime = 0})
        .solved();
  };
  const auto tryPlacements = [&](double lift, int placements, GeneratedProblem& problem) {
    for (int placement = 0; placement < placements; ++placement) {
      Eigen::Vector3d target;
      problem.scene = placeStructure(options.family, rng, lift, target);
      CheckerOptions checking;
      checking.selfCollision = options.selfCollision;
      const auto exact = makeSceneChecker(kDefaultSceneChecker, robot, problem.scene, checking);
      const CollisionChecker& checker = *exact;
      const auto nearTarget = [&](const Eigen::Vector3d& p) {
        return (p - target).norm() <= options.reach;
      };
      // In front of the robot, between it and the structure, above its base (raised with it).
      const auto ready = [lift](const Eigen::Vector3d& p) {
        return p.x() > 0.15 && p.x() < 0.35 && std::abs(p.y()) < 0.25 && p.z() > 0.3 + lift &&
               p.z() < 0.7 + lift;
      };
      if (findConfiguration(robot, tip, checker, options.samplesPerAttempt, rng, nearTarget,
                            problem.goal) &&
          findConfiguration(robot, tip, checker, options.samplesPerAttempt, rng, ready,
                            problem.start)) {
        takeTurnsNearestStart(robot, problem.start, problem.goal);
        if (options.solvableWithin == 0 || hasPath(exact, problem)) return true;
      }
    }
    return false;
  };
  while (problems.size() < options.count) {
    GeneratedProblem problem;
    bool found = tryPlacements(lifts.front(), kPlacements, problem);
    if (!found && problems.empty()) {
      const std::vector<double> byReach = liftsByReach(robot, tip, options.family, options.reach);
      for (std::size_t i = 0; i < byReach.size() && i < kLiftsTried && !found; ++i) {
        found = tryPlacements(byReach[i], kPlacementsPerLift, problem);
        if (found) lifts = {byReach[i]};
      }
    }
    if (!found) {
      throw Error("no free start and goal" +
                  std::string(options.solvableWithin > 0 ? " joined by a path" : "") +
                  " for problem " + std::to_string(problems.size() + 1) + " of family '" +
                  std::string(toString(options.family)) + "' in " + std::to_string(kPlacements) +
                  " placements: can robot '" + robot.name() + "' reach into it with link '" +
                  robot.links()[static_cast<std::size_t>(tip)].name + "'?");
    }
    problems.push_back(std::move(problem));
  }
  return problems;
}

void writeProblems(const std::filesystem::path& folder, const Robot& robot,
                   const std::vector<GeneratedProblem>& problems, const std::string& group) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw FileError(folder.string() + ": cannot create the folder: " + error.message());
  const std::vector<std::string> joints = robot.actuatedJointNames();
  for (std::size_t i = 0; i < problems.size(); ++i) {
    std::string number = std::to_string(i + 1);
    number.insert(0, number.size() < 4 ? 4 - number.size() : 0, '0');
    const PlanRequest request{group, {joints, problems[i].start}, {joints, problems[i].goal}};
    writeFileAtomically(folder / ("scene" + number + ".yaml"),
                        moveItSceneYaml(problems[i].scene, robot.name()), "MoveIt scene");
    writeFileAtomically(folder / ("request" + number + ".yaml"), moveItRequestYaml(request),
                        "MoveIt request");
  }
}

}  // namespace fastron::experiments
