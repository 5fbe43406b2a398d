#pragma once
// The robot the SRDF and MoveIt-request targets read against: the shipped Panda (with its
// meshes: the robot MoveIt files are written for), loaded once.

#include "fastron/geometry/robot_library.h"

namespace fastron::fuzz {

inline const Robot& panda() {
  static const Robot robot = loadRobot("panda");
  return robot;
}

}  // namespace fastron::fuzz
