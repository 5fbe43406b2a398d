#pragma once
// The float chain of RobotPointKinematics (point_kinematics.h) as plain data, for the batched
// kinematics compiled once per SIMD path (src/geometry/lane_kinematics_impl.h). Kept apart, with
// no include but <cstddef>, so that those files see no inline function from outside.

#include <cstddef>

namespace fastron::detail {

/// Largest number of actuated joints between the base and a control point (kMaxKinematicSteps).
inline constexpr std::size_t kMaxLaneSteps = 64;

/// (Plain arrays: the code compiled per SIMD path calls no inline function from outside, not
/// even std::array's operator[].)
struct LaneStep {
  int parent = -1;
  int joint = 0;
  float scale = 1, offset = 0;  // the joint's value: scale * q[joint] + offset (mimic joints)
  int prismatic = 0;
  float fixed[12] = {};  // NOLINT(modernize-avoid-c-arrays): the 3x4 transform, row by row
};
struct LanePoint {
  int step = -1;
  float local[3] = {};  // NOLINT(modernize-avoid-c-arrays)
};
struct LaneChain {
  const LaneStep* steps = nullptr;
  std::size_t stepCount = 0;
  const LanePoint* points = nullptr;
  std::size_t pointCount = 0;
  std::size_t dof = 0;
};

}  // namespace fastron::detail
