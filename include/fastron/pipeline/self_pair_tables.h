#pragma once
// A robot's self-pair tables (self_pair_table.h), built once per robot and kept in the cache
// beside its self-collision model: they depend on the robot alone (kinematics, collision shapes,
// allowed pairs, padding), so every scene, checker and later run reuses them. With them, FCL's
// checks of a robot of meshes with self-collision read a table for the pairs that one or two
// joints turn against each other (the mesh Panda's link 5, link 7 and hand) instead of asking
// FCL about meshes millimetres apart.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/self_pair_table.h"

namespace FASTRON_API fastron {
namespace pipeline {

/// How a robot's self-pair tables are built, and where they are kept.
struct SelfPairTablesOptions {
  /// Metres the levers may take off a node's distance (CheckerOptions::selfPairSlack): smaller
  /// proves more pairs apart and costs more nodes. 7 mm: the mesh Panda's four tables in 5 s
  /// on two cores, verification 3.5 times faster than dense checking (docs/geometry.md).
  double slack = 0.007;
  double padding = 0;  ///< metres the robot's shapes are grown by (CheckerOptions::padding)
  /// Where tables are kept: empty for defaultCacheDirectory() (self_model.h).
  std::filesystem::path cacheDirectory;
};

/// A 64-bit hash of all the tables depend on: the robot's collision description (as
/// selfModelKey's), the options' slack and padding, and the tables' format and node limit.
std::uint64_t selfPairTablesKey(const Robot& robot, const SelfPairTablesOptions& options);

/// The cache file of `robot`'s tables: NAME-KEY.self-pairs in the cache directory.
std::filesystem::path selfPairTablesFile(const Robot& robot, const SelfPairTablesOptions& options);

/// True when `robot` has a self pair that holds a mesh: the only robots tables are built for
/// (FCL's distance of two primitives costs as much as a lookup).
bool hasMeshSelfPairs(const Robot& robot);

struct SelfPairTables {
  /// Null when the robot has no self pair of meshes, else its tables (possibly none: no pair
  /// that one or two coordinates alone turn): CheckerOptions::selfPairTables.
  std::shared_ptr<const std::vector<SelfPairTable>> tables;
  std::filesystem::path file;  ///< where they are kept; empty when the robot needs none
  bool fromCache = false;      ///< read, not built
  double buildSeconds = 0;     ///< 0 when read from the cache
  /// Why the tables built could not be kept (the cache folder cannot be made or written): they
  /// serve this run all the same. Empty when kept or read.
  std::string warning;
};

/// `robot`'s self-pair tables: read from selfPairTablesFile when it is there, readable and of
/// this key and robot, else built on every core (FclChecker, CheckerOptions::selfPairSlack) and
/// written there atomically. Not thread-safe for one cache file; two processes that build at once
/// write the same tables.
SelfPairTables selfPairTables(const Robot& robot, const SelfPairTablesOptions& options = {});

}  // namespace pipeline
}  // namespace fastron
