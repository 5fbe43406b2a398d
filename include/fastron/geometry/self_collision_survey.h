#pragma once
// Which pairs of a robot's links collide with each other, and how often: the sampling step of
// MoveIt Setup Assistant's "self-collisions" page, for any robot we load. Its output is the
// list of pairs a robot description should allow (robots.yaml's allowed_collisions, an SRDF's
// disable_collisions) before self-collision checks mean anything.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {

/// Why a pair would be disabled by Setup Assistant's rules, or Enabled when none applies.
enum class PairVerdict {
  Default,  ///< in collision at home: actuated joints at 0 (or the nearest limit), others held
  Always,   ///< in collision in at least SelfCollisionOptions::alwaysShare of the samples
  Never,    ///< never in collision over all samples (disabling it only saves time)
  Enabled,  ///< collides sometimes: a real self-collision to keep checking
};
std::string_view toString(PairVerdict verdict);

struct LinkPairSurvey {
  std::string linkA, linkB;
  std::size_t collisions = 0;  ///< samples in which the pair collides
  bool atHome = false;
  PairVerdict verdict = PairVerdict::Enabled;
};

struct SelfCollisionOptions {
  std::size_t samples = 10000;  ///< uniform configurations within the joint limits
  double alwaysShare = 0.95;    ///< Setup Assistant's "always in collision" threshold
  std::uint64_t seed = 1;
};

struct SelfCollisionSurvey {
  std::size_t samples = 0;
  std::size_t configurationsInCollision = 0;  ///< samples with at least one Enabled pair touching
  std::size_t configurationsBefore = 0;       ///< samples with any pair touching
  /// Every pair of links with geometry that the robot does not already allow (adjacent links and
  /// its allowedCollisions() are skipped), most colliding first.
  std::vector<LinkPairSurvey> pairs;
};

/// Samples the robot's configurations and checks every link pair with FCL. Throws
/// InvalidArgument for zero samples or a threshold outside (0, 1].
SelfCollisionSurvey surveySelfCollisions(const Robot& robot, const SelfCollisionOptions& options);

}  // namespace fastron
