#include "fastron/geometry/checker_options.h"

#include <string>

#include "fastron/core/error.h"

namespace fastron {

Shape paddedShape(const Robot& robot, std::size_t index, const CheckerOptions& options) {
  const LinkShape& s = robot.shapes()[index];
  try {
    return inflate(s.shape, options.padding);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument("link '" + robot.links()[static_cast<std::size_t>(s.link)].name +
                          "': " + e.what());
  }
}

std::vector<std::uint8_t> allowedObstacleContacts(const Robot& robot, const Scene& scene) {
  const auto& obstacles = scene.obstacles();
  std::vector<std::uint8_t> allowed(robot.shapes().size() * obstacles.size(), 0);
  bool any = false;
  for (std::size_t s = 0; s < robot.shapes().size(); ++s) {
    const std::string& link = robot.links()[static_cast<std::size_t>(robot.shapes()[s].link)].name;
    for (std::size_t o = 0; o < obstacles.size(); ++o) {
      if (scene.allowedCollisions.allowed(link, obstacles[o].name)) {
        allowed[s * obstacles.size() + o] = 1;
        any = true;
      }
    }
  }
  if (!any) allowed.clear();
  return allowed;
}

}  // namespace fastron
