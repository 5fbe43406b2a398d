// Trajectory optimisation on a Fastron model: learn Baxter's C-space among three boxes from FCL
// labels, then, for ten queries whose straight line collides, push that line out of collision
// along the gradient of the model's collision cost (CHOMP-style), verify the result with FCL and
// let the model learn what verification finds. Built with the project and run by the test suite;
// `fastron bench optimize` measures the same against RRT-Connect.

#include <fastron/geometry/fcl_checker.h>
#include <fastron/geometry/robot_features.h>
#include <fastron/geometry/robot_library.h>
#include <fastron/geometry/scene_file.h>
#include <fastron/planning/trajectory_optimization.h>
#include <fastron/proxy/proxy_collision_detector.h>

#include <iostream>
#include <memory>
#include <random>

int main() {
  const fastron::Robot baxter = fastron::loadRobot("baxter");  // the right arm, 7 joints
  const fastron::Scene scene =
      fastron::loadScene(fastron::dataDirectory() / "scenes" / "baxter_three_boxes.yaml");
  auto fcl = std::make_shared<const fastron::FclChecker>(baxter, scene);
  const fastron::JointLimits limits = baxter.limits();
  // Task-space features (control points on the arm) and their default kernel.
  const auto kind = fastron::FeatureKind::Kinematic;
  fastron::ProxyCollisionDetector proxy(fcl, fastron::robotFeatures(baxter, kind),
                                        fastron::defaultProxyParams(kind));
  proxy.initialize(3000);

  const double resolution = 0.02;  // rad between the states FCL checks
  std::mt19937_64 rng(1);
  const auto uniform = [&] {
    Eigen::VectorXd q(7);
    for (Eigen::Index j = 0; j < 7; ++j)
      q[j] = std::uniform_real_distribution<double>(limits.lower()[j], limits.upper()[j])(rng);
    return q;
  };
  int solved = 0, queries = 0;
  while (queries < 10) {
    const Eigen::VectorXd start = uniform(), goal = uniform();
    if (fcl->inCollision({start.data(), 7}) || fcl->inCollision({goal.data(), 7}) ||
        fastron::checkPath(*fcl, {start, goal}, resolution).valid()) {
      continue;  // free ends whose straight line collides
    }
    ++queries;
    const fastron::VerifiedTrajectory out =
        fastron::optimizeVerified(proxy, fcl, start, goal, resolution, {});
    const bool free = out.status == fastron::PlanStatus::Solved;
    solved += free ? 1 : 0;
    std::cout << "query " << queries << ": " << (free ? "free under FCL" : out.failure) << ", "
              << out.iterations << " iterations in " << out.rounds << " round(s), "
              << out.totalTime().count() / 1e6 << " ms, length " << fastron::pathLength(out.path)
              << " rad (straight line " << (goal - start).norm() << ")\n";
    // The guarantee: a solved path is free under FCL at the resolution it was verified at.
    if (free && !fastron::checkPath(*fcl, out.path, resolution).valid()) return 1;
  }
  std::cout << solved << " of " << queries << " straight lines optimised to FCL-free paths\n";
  return 0;
}
