#pragma once
// Obstacle scenes that change over time: obstacles with a pose, each optionally moving.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/types.h"
#include "fastron/geometry/allowed_collisions.h"
#include "fastron/geometry/shapes.h"

namespace FASTRON_API fastron {

/// Each step the obstacle moves in a uniformly random direction by a length drawn uniformly from
/// [minStep, maxStep], reflected back into `bounds` (its position stays inside them).
struct RandomWalk {
  double minStep = 0.01, maxStep = 0.04;
  Eigen::AlignedBox3d bounds;
  std::uint64_t seed = 1;
};

/// The obstacle's position goes round a circle about `axis`; its orientation does not change.
struct CircularPath {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.1;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double period = 100;  ///< steps per revolution
  double phase = 0;     ///< angle at step 0 (radians)
};

/// Poses at given times (steps), interpolated linearly (positions) and by slerp (rotations),
/// held before the first and after the last.
struct ScriptedPoses {
  std::vector<double> times;
  std::vector<Eigen::Isometry3d> poses;
};

/// How an obstacle moves as the scene steps (a robot's motion is planning/motion.h's).
using ObstacleMotion = std::variant<RandomWalk, CircularPath, ScriptedPoses>;

struct Obstacle {
  std::string name;
  Shape shape;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::optional<ObstacleMotion> motion;
};

/// Joint positions by name (a MoveIt joint_state, or joint_constraints).
struct NamedPositions {
  std::vector<std::string> names;
  std::vector<double> positions;
};

class Scene {
 public:
  /// Throws InvalidArgument for an empty or repeated name, an invalid shape, a non-finite pose
  /// or an invalid motion (empty bounds, maxStep < minStep, period <= 0, unordered key times).
  void add(Obstacle obstacle);
  void remove(std::string_view name);
  void setPose(std::string_view name, const Eigen::Isometry3d& pose);
  /// Replaces an obstacle's shape, e.g. a camera's cloud by the next frame's (the pose and motion
  /// stay). Throws InvalidArgument for an unknown name or an invalid shape.
  void setShape(std::string_view name, Shape shape);
  const Obstacle& obstacle(std::string_view name) const;
  const std::vector<Obstacle>& obstacles() const { return obstacles_; }
  std::size_t size() const { return obstacles_.size(); }
  /// The same scene with every obstacle grown by `margin` metres in every direction, meshes
  /// excepted (they stay as they are): labels that leave the robot that much room. Throws
  /// InvalidArgument for a margin that is negative or not finite.
  Scene grown(double margin) const;

  /// Advances time by `steps`, moving every obstacle that has a motion. Deterministic: random
  /// walks draw from their own seeded generators.
  void step(std::size_t steps = 1);
  double time() const { return time_; }

  /// Where the robot's root link sits in the world.
  Eigen::Isometry3d robotBase = Eigen::Isometry3d::Identity();
  /// Link pairs that may touch, beyond the robot's adjacent links (self-collision only).
  AllowedCollisionMatrix allowedCollisions;
  /// Where the scene puts the robot's joints (a MoveIt PlanningScene's robot_state.joint_state):
  /// robotForRequest holds the joints a plan does not move there. Empty when the file says none.
  NamedPositions robotState;

 private:
  std::size_t indexOf(std::string_view name) const;
  void applyMotion(std::size_t i);

  std::vector<Obstacle> obstacles_;
  std::vector<Rng> walkers_;  // per obstacle, used by random walks
  double time_ = 0;
};

/// rpy (roll, pitch, yaw about fixed x, y, z, as in URDF) and position as a pose.
Eigen::Isometry3d makePose(const Eigen::Vector3d& position,
                           const Eigen::Vector3d& rpy = Eigen::Vector3d::Zero());

}  // namespace fastron
