#pragma once
// A robot's self-collision model, learned once per robot and kept in a cache: self-collision
// depends on the robot alone (its kinematics, collision shapes and allowed pairs), not on the
// scene, so every scene and every later run can reuse it.

#include <cstdint>
#include <filesystem>
#include <memory>

#include <string>

#include "fastron/core/collision_checker.h"
#include "fastron/core/export.h"
#include "fastron/core/joint_limits.h"
#include "fastron/core/model.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {
namespace pipeline {

/// How a self-collision model is trained, and where it is kept.
struct SelfModelOptions {
  std::size_t samples = 20000;  ///< uniform configurations labelled by FCL (self-collision on)
  std::size_t updates = 3;      ///< active-learning updates after them
  std::uint64_t seed = 1;
  double padding = 0;  ///< metres the robot's shapes are grown by (CheckerOptions::padding)
  /// Where models are kept: empty for defaultCacheDirectory().
  std::filesystem::path cacheDirectory;
};

/// $FASTRON_CACHE_DIR if set, else $XDG_CACHE_HOME/fastron, else $HOME/.cache/fastron; throws
/// FileError when none of them is set.
std::filesystem::path defaultCacheDirectory();

/// A 64-bit hash of all a self-collision model depends on: the robot's kinematics
/// (kinematicsChecksum: links, joints, held positions, actuated joints, mimics), its collision
/// shapes on their links, the link pairs its description allows (an SRDF's disabled collisions,
/// a catalogue's pairs), and the options' samples, updates, seed and padding. A changed URDF or
/// SRDF changes it.
std::uint64_t selfModelKey(const Robot& robot, const SelfModelOptions& options);

/// The cache file of `robot`'s model: NAME-KEY.fastron in the cache directory.
std::filesystem::path selfModelFile(const Robot& robot, const SelfModelOptions& options);

/// The joint limits a self-collision model of `robot` learns on: the robot's, with each coordinate
/// of more than a turn (coordinatesOfMoreThanATurn: a UR arm's +-2 pi) narrowed to [-pi, pi]. A
/// pose repeats every turn, so one turn holds every answer, and a model of two turns must learn
/// each answer twice per such joint: on a UR3 with five joints of two turns, 20000 labels made a
/// model of accuracy 0.811 at the 5000-point cap over two turns, 0.907 with 3214 points over one
/// (docs/log/2026-12-01-an-arms-collisions-with-itself.md).
JointLimits selfModelLimits(const Robot& robot);

/// `model`, a self-collision model over `robot`'s actuated joints, as a checker of the robot's
/// configurations named `name`: each coordinate of more than a turn that `model` learned on one
/// turn, [-pi, pi] (as selfModelLimits gives it), is wrapped onto it (the same pose) before the
/// model answers; a model of the robot's own limits (a file of an earlier version) answers as it
/// is. Throws InvalidArgument on a null model or one of another number of joints.
std::shared_ptr<const CollisionChecker> selfModelChecker(const Robot& robot,
                                                         std::shared_ptr<const Model> model,
                                                         std::string name = "Fastron self");

struct SelfModel {
  std::shared_ptr<const Model> model;
  std::filesystem::path file;  ///< where it is kept
  bool fromCache = false;      ///< read, not trained
  double trainSeconds = 0;     ///< labelling and training; 0 when read from the cache
};

/// `robot`'s self-collision model over its actuated joints within selfModelLimits (joint
/// features; an RQ kernel, gamma 5 and beta 500, as measured in
/// docs/log/2026-11-25-a-self-collision-model-learned-once.md, "A self-collision model learned
/// once"; ask it through selfModelChecker): read from selfModelFile when it is there, readable and
/// of those limits, else trained on FCL's labels of the robot alone and written there (to a
/// temporary file first, then moved: a run stopped halfway leaves no half file; two runs that
/// train at once write the same model). Throws FileError when the cache directory cannot be made
/// or written. Not thread-safe for one cache file.
SelfModel selfCollisionModel(const Robot& robot, const SelfModelOptions& options = {});

}  // namespace pipeline
}  // namespace fastron
