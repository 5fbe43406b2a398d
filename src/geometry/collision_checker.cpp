#include "fastron/geometry/collision_checker.h"

#include <string>

#include "fastron/core/error.h"
#include "fastron/core/joint_limits.h"

namespace fastron {

bool CollisionChecker::inCollision(std::span<const double> q) const {
  checkConfiguration(q, dof());
  calls_.fetch_add(1, std::memory_order_relaxed);
  return check(q.data());
}

std::vector<std::uint8_t> CollisionChecker::inCollisionBatch(const Configurations& q) const {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(q.rows()));
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    out[static_cast<std::size_t>(i)] =
        inCollision({q.row(i).data(), static_cast<std::size_t>(q.cols())});
  }
  return out;
}

FunctionChecker::FunctionChecker(std::string name, std::size_t dof,
                                 std::function<bool(const double*)> fn)
    : name_(std::move(name)), dof_(dof), fn_(std::move(fn)) {
  if (dof_ == 0) throw InvalidArgument("checker '" + name_ + "': dof must be at least 1");
  if (!fn_) throw InvalidArgument("checker '" + name_ + "': no function given");
}

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
