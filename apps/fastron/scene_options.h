#pragma once
// The options that choose a scene and its exact checker, declared once for every command:
// --scene, --allow, --self-collision, --padding, --checker.

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/geometry/scene.h"
#include "fastron/geometry/scene_checker.h"
#include "fastron/geometry/scene_checkers.h"

namespace fastron::cli {

struct SceneOptions {
  std::string file;                ///< --scene: the project's YAML or a MoveIt PlanningScene
  std::vector<std::string> allow;  ///< --allow: LINK:OBSTACLE pairs that may touch
  bool selfCollision = false;      ///< --self-collision
  bool selfPairTables = true;      ///< not --no-self-pair-tables
  double padding = 0;              ///< --padding: grows the robot's shapes (m)
  std::string checker{kDefaultSceneChecker};  ///< the exact checker's name (scene_checkers.h)
};

/// What differs between the commands that declare the scene options.
struct SceneOptionUse {
  bool sceneRequired = true;
  /// What --self-collision means to the command.
  std::string selfCollisionHelp = "also check the robot against itself";
  /// What the exact checker does in the command, after "the exact checker that ".
  std::string checkerRole = "decides";
  /// The option naming the exact checker (plan's --checker chooses what it plans on).
  std::string checkerOption = "--checker";
  bool padding = true;  ///< offer --padding
  /// offer --no-self-pair-tables (commands that check many states: checkerOptionsFor)
  bool selfPairTables = true;
};

void addSceneOptions(CLI::App& cmd, SceneOptions& options, const SceneOptionUse& use = {});

/// The scene file (an empty scene when none was given) with the --allow pairs allowed. Throws
/// InvalidArgument naming a pair not of the form LINK:OBSTACLE, and what the reader throws.
Scene sceneFromOptions(const SceneOptions& options);

/// The exact checker's options: self-collision and padding.
CheckerOptions checkerOptionsFrom(const SceneOptions& options);

/// checkerOptionsFrom, and with --self-collision on a robot whose self pairs hold meshes (unless
/// --no-self-pair-tables), the robot's self-pair tables (pipeline::selfPairTables: read from the
/// cache, or built and kept there), said on one line of std::cout after `label`.
CheckerOptions checkerOptionsFor(const SceneOptions& options, const Robot& robot,
                                 std::string_view label);

/// The exact checker the options name, on `robot` in `scene` (checkerOptionsFor's options).
std::shared_ptr<SceneChecker> checkerFromOptions(const SceneOptions& options, const Robot& robot,
                                                 const Scene& scene, std::string_view label);

}  // namespace fastron::cli
