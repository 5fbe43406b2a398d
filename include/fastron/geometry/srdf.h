#pragma once
// MoveIt's semantic robot description (SRDF), read as MoveIt reads it: the link pairs it never
// checks against each other, and the planning groups.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/allowed_collisions.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {

/// A planning group: the joints a plan for it moves.
struct SrdfGroup {
  std::string name;
  /// Its movable joints that mimic none, in the order the group lists them (a chain from base to
  /// tip; a subgroup's joints where the subgroup is named), each once. As MoveIt resolves them:
  /// <joint> is that joint, <link> the link's parent joint, <chain> the joints between base_link
  /// and tip_link, <group> the subgroup's joints. Fixed and mimic joints give none.
  std::vector<std::string> joints;
};

struct Srdf {
  /// `<disable_collisions link1 link2/>`: pairs that touch by construction or can never meet.
  AllowedCollisionMatrix disabledCollisions;
  std::vector<SrdfGroup> groups;  ///< in file order
  /// What was skipped, one line each naming the file, line and element: entries naming links,
  /// joints or groups the robot lacks (MoveIt warns about them and skips them too), and an SRDF
  /// written for a robot of another name.
  std::vector<std::string> warnings;

  /// The group of this name; throws InvalidArgument naming it and the groups there are.
  const SrdfGroup& group(std::string_view name) const;
};

/// Reads an SRDF for `robot`: disabled collisions and groups (end effectors, virtual and passive
/// joints are checked for names the robot lacks, and otherwise not needed here). Throws FileError
/// naming the file, and the line where it can: malformed XML, a root other than <robot>, a
/// `disable_collisions` without link1 or link2, a group without a name, a chain without both
/// ends or whose base is not an ancestor of its tip, groups that contain each other.
Srdf loadSrdf(const std::filesystem::path& file, const Robot& robot);

/// The same from a string; `source` names it in messages.
Srdf parseSrdf(const std::string& xml, const std::string& source, const Robot& robot);

}  // namespace fastron
