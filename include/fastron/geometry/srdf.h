#pragma once
// MoveIt's semantic robot description (SRDF): the link pairs it never checks against each other.

#include <filesystem>
#include <string>

#include "fastron/core/export.h"
#include "fastron/geometry/allowed_collisions.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {

/// The `<disable_collisions link1=".." link2=".."/>` pairs of an SRDF for `robot`: pairs that
/// touch by construction or can never meet, which MoveIt skips in self-collision checks. Other
/// SRDF elements (groups, states, end effectors) are not needed for collision checking and are
/// ignored. Throws FileError naming the file, and the line where it can: malformed XML, a root
/// other than <robot>, an SRDF written for a robot of another name, a `disable_collisions`
/// without link1 or link2, or a link the robot does not have.
AllowedCollisionMatrix loadSrdfDisabledCollisions(const std::filesystem::path& file,
                                                  const Robot& robot);

/// The same from a string; `source` names it in messages.
AllowedCollisionMatrix parseSrdfDisabledCollisions(const std::string& xml,
                                                   const std::string& source, const Robot& robot);

}  // namespace fastron
