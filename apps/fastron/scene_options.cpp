#include "scene_options.h"

#include <iostream>

#include "fastron/core/error.h"
#include "fastron/experiments/report_text.h"
#include "fastron/geometry/scene_file.h"

namespace fastron::cli {

void addSceneOptions(CLI::App& cmd, SceneOptions& options, const SceneOptionUse& use) {
  CLI::Option* scene = cmd.add_option("--scene", options.file,
                                      "scene file: the project's YAML or a MoveIt PlanningScene")
                           ->check(CLI::ExistingFile);
  if (use.sceneRequired) scene->required();
  cmd.add_option("--allow", options.allow,
                 "LINK:OBSTACLE pairs that may touch (e.g. a grasped object and the hand)")
      ->delimiter(',');
  cmd.add_flag("--self-collision", options.selfCollision, use.selfCollisionHelp);
  if (use.selfPairTables) {
    cmd.add_flag("!--no-self-pair-tables", options.selfPairTables,
                 "with --self-collision on a robot of meshes: check its self pairs without the "
                 "robot's tables of their distances (built once and kept in the cache, "
                 "$FASTRON_CACHE_DIR, else ~/.cache/fastron)");
  }
  if (use.padding) {
    cmd.add_option("--padding", options.padding, "grow the robot's shapes by this much (m)")
        ->check(CLI::NonNegativeNumber);
  }
  std::vector<std::string> names;
  std::string list;
  for (const SceneCheckerKind& kind : sceneCheckerKinds()) {
    names.push_back(kind.name);
    list += (list.empty() ? "" : "; ") + kind.name + ": " + kind.description;
  }
  cmd.add_option(use.checkerOption, options.checker,
                 "the exact checker that " + use.checkerRole + " (" + list + ")")
      ->capture_default_str()
      ->transform(CLI::IsMember(names, CLI::ignore_case));
}

Scene sceneFromOptions(const SceneOptions& options) {
  if (options.file.empty() && !options.allow.empty())
    throw InvalidArgument("--allow needs --scene");
  Scene scene = options.file.empty() ? Scene{} : loadScene(options.file);
  for (const std::string& pair : options.allow) {
    const auto colon = pair.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == pair.size()) {
      throw InvalidArgument("--allow '" + pair + "' is not LINK:OBSTACLE");
    }
    scene.allowedCollisions.allow(pair.substr(0, colon), pair.substr(colon + 1));
  }
  return scene;
}

CheckerOptions checkerOptionsFrom(const SceneOptions& options) {
  CheckerOptions checking;
  checking.selfCollision = options.selfCollision;
  checking.padding = options.padding;
  return checking;
}

CheckerOptions checkerOptionsFor(const SceneOptions& options, const Robot& robot,
                                 std::string_view label) {
  CheckerOptions checking = checkerOptionsFrom(options);
  if (!(options.selfCollision && options.selfPairTables)) return checking;
  const pipeline::SelfPairTables tables =
      pipeline::selfPairTables(robot, {.padding = options.padding});
  if (!tables.tables) return checking;  // no self pair of meshes
  checking.selfPairTables = tables.tables;
  std::cout << label << experiments::selfPairTablesText(tables) << '\n';
  if (!tables.warning.empty()) std::cerr << "fastron: warning: " << tables.warning << '\n';
  return checking;
}

std::shared_ptr<SceneChecker> checkerFromOptions(const SceneOptions& options, const Robot& robot,
                                                 const Scene& scene, std::string_view label) {
  return makeSceneChecker(options.checker, robot, scene, checkerOptionsFor(options, robot, label));
}

}  // namespace fastron::cli
