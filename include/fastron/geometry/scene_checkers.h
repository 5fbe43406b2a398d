#pragma once
// The exact checkers by name: what `--checker`, the oracles of `sample` / `train` / `eval` /
// `plan`, Python's `scene_checker` and the pipeline build. Adding a backend: its header and source
// (a SceneChecker), and one entry in the table of scene_checkers.cpp.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/scene_checker.h"

namespace FASTRON_API fastron {

/// The checker the commands and the pipeline use unless told otherwise.
inline constexpr std::string_view kDefaultSceneChecker = "fcl";

/// A backend's name (lower case, as `--checker` takes it) and what it is.
struct SceneCheckerKind {
  std::string name;
  std::string description;
};

/// Every backend, the default first.
std::vector<SceneCheckerKind> sceneCheckerKinds();

/// The backend `name` on `robot` in `scene`. Throws InvalidArgument naming the value and the
/// known names when there is no such backend, and what the backend's constructor throws (a robot
/// without actuated joints, a padding it cannot apply).
std::shared_ptr<SceneChecker> makeSceneChecker(std::string_view name, Robot robot,
                                               const Scene& scene, CheckerOptions options = {});

}  // namespace fastron
