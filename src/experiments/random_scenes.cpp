#include "fastron/experiments/random_scenes.h"

#include <cmath>

namespace fastron::experiments {

Scene randomCubes(std::size_t maxCubes, double minSide, double maxSide, double reach, Rng& rng) {
  std::uniform_int_distribution<std::size_t> count(1, maxCubes);
  std::uniform_real_distribution<double> side(minSide, maxSide), unit(-1.0, 1.0),
      yaw(-3.14159, 3.14159);
  Scene scene;
  const std::size_t n = count(rng);
  while (scene.size() < n) {
    const double s = side(rng);
    const Eigen::Vector3d c(reach * unit(rng), reach * unit(rng), reach * std::abs(unit(rng)));
    // In reach, and clear of the base: a cube holding the base would fill the whole C-space.
    if (c.norm() > reach || c.norm() < s * 0.87 + 0.08) continue;
    scene.add({"cube" + std::to_string(scene.size() + 1), Box{Eigen::Vector3d::Constant(s)},
               makePose(c, {0, 0, yaw(rng)}), std::nullopt});
  }
  return scene;
}

}  // namespace fastron::experiments
