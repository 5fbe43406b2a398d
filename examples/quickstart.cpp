// Quick start: learn the C-space of an analytic 2-D world, keep the model current while the
// obstacle moves, and query it. Built with the project and run by the test suite.

#include <fastron/core/model_file.h>
#include <fastron/proxy/proxy_collision_detector.h>

#include <cmath>
#include <iostream>
#include <memory>

int main() {
  // Any exact checker works as the oracle; here a disc of radius 0.5 around a moving centre.
  double centre = -1.0;
  auto oracle = std::make_shared<fastron::FunctionChecker>(
      "disc", 2, [&](const double* q) { return std::hypot(q[0] - centre, q[1]) < 0.5; });
  const fastron::JointLimits limits(Eigen::Vector2d(-2, -2), Eigen::Vector2d(2, 2));

  fastron::ProxyParams params;
  params.train.kernel.gamma = 30;  // kernel width in the scaled input space [-1, 1]^2
  params.train.beta = 5;           // conditional bias: pads obstacles (fewer false "free")
  params.activeLearning.maxSamples = 300;
  fastron::ProxyCollisionDetector proxy(oracle, limits, params);

  proxy.initialize(1500);  // label 1500 uniform samples, run Algorithm 1
  for (int step = 0; step < 20; ++step) {
    centre += 0.1;                                    // the world changes...
    const fastron::StepReport report = proxy.step();  // ...Algorithm 2 + relabel + Algorithm 1
    std::cout << "step " << step << ": |S| = " << report.update.supportCount << ", "
              << report.labelled << " labels\n";
  }

  const std::shared_ptr<const fastron::Model> model = proxy.model();  // immutable snapshot
  const double inside[2] = {centre, 0.1}, outside[2] = {centre, 1.5};
  std::cout << "at the centre: " << (model->inCollision(inside) ? "collision" : "free")
            << "; far away: " << (model->inCollision(outside) ? "collision" : "free") << '\n';
  fastron::saveModel(*model, "quickstart.fastron");
  return model->inCollision(inside) && !model->inCollision(outside) ? 0 : 1;
}
