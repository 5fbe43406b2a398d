#include "fastron/geometry/scene_checkers.h"

#include <array>
#include <functional>

#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"

namespace fastron {
namespace {

struct Backend {
  std::string_view name;
  std::string_view description;
  std::shared_ptr<SceneChecker> (*make)(Robot robot, const Scene& scene, CheckerOptions options);
};

template <class Checker>
std::shared_ptr<SceneChecker> make(Robot robot, const Scene& scene, CheckerOptions options) {
  return std::make_shared<Checker>(std::move(robot), scene, options);
}

// The default first. A new backend: one line here.
constexpr std::array kBackends{
    Backend{"fcl", "forward kinematics, then FCL 0.7 (meshes, distances, proofs of free motions)",
            make<FclChecker>},
    Backend{"gjk", "forward kinematics, then libccd's GJK on convex shapes (a mesh: its hull)",
            make<GjkChecker>},
};

}  // namespace

std::vector<SceneCheckerKind> sceneCheckerKinds() {
  std::vector<SceneCheckerKind> kinds;
  for (const Backend& b : kBackends)
    kinds.push_back({std::string(b.name), std::string(b.description)});
  return kinds;
}

std::shared_ptr<SceneChecker> makeSceneChecker(std::string_view name, Robot robot,
                                               const Scene& scene, CheckerOptions options) {
  for (const Backend& b : kBackends) {
    if (b.name == name) return b.make(std::move(robot), scene, options);
  }
  std::string known;
  for (const Backend& b : kBackends) known += (known.empty() ? "" : ", ") + std::string(b.name);
  throw InvalidArgument("unknown checker '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace fastron
