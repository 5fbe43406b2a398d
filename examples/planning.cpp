// Planning with a Fastron model: learn Baxter's C-space among a box from FCL labels, plan with
// RRT-Connect on the model, and verify and repair the plan with FCL. Built with the project and
// run by the test suite.

#include <fastron/geometry/fcl_checker.h>
#include <fastron/geometry/robot_library.h>
#include <fastron/geometry/scene_file.h>
#include <fastron/planning/verify_repair.h>
#include <fastron/proxy/proxy_collision_detector.h>
#include <ompl/util/Console.h>

#include <iostream>
#include <memory>

int main() {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);  // OMPL's own console output: warnings only

  fastron::Robot baxter = fastron::loadRobot("baxter");  // the right arm, 7 joints
  const fastron::Scene scene =
      fastron::loadScene(fastron::dataDirectory() / "scenes" / "baxter_one_box.yaml");
  auto fcl = std::make_shared<const fastron::FclChecker>(baxter, scene);
  const fastron::JointLimits limits = baxter.limits();

  fastron::ProxyParams params;
  params.train.kernel.gamma = 5;
  params.train.beta = 500;  // err on the side of "collision"
  fastron::ProxyCollisionDetector proxy(fcl, limits, params);
  proxy.initialize(3000);

  Eigen::VectorXd start(7), goal(7);
  start << -1.2, 0.3, 0.0, 1.2, 0.0, 0.5, 0.0;
  goal << 1.2, 0.3, 0.0, 1.2, 0.0, 0.5, 0.0;
  const fastron::PlannerOptions options{.type = fastron::PlannerType::RrtConnect,
                                        .resolution = 0.03,  // rad between checked states
                                        .timeLimit = 5,
                                        .verify = {}};
  const fastron::VerifiedPlan plan =
      fastron::planVerified(proxy.calibratedModel(), fcl, limits, start, goal, options);
  if (!plan.solved()) {
    std::cout << "no valid path: " << plan.failure << '\n';
    return 1;
  }
  std::cout << plan.path.size() << " waypoints; plan " << plan.planTime.count() / 1e6
            << " ms, verify " << plan.verifyTime.count() / 1e6 << " ms, repair "
            << plan.repairTime.count() / 1e6 << " ms, " << plan.invalidStretches
            << " stretch(es) repaired\n";
  // The guarantee: the final path is free under FCL at the motion resolution.
  return fastron::checkPath(*fcl, plan.path, options.resolution).valid() ? 0 : 1;
}
