#include "fastron/experiments/cspace_experiment.h"

#include <cstdio>
#include <sstream>

#include "fastron/baselines/fastron_classifier.h"
#include "fastron/baselines/incremental_svm.h"
#include "fastron/baselines/sparse_svm.h"
#include "fastron/core/active_learning.h"
#include "fastron/experiments/random_scenes.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/proxy/labelling.h"

namespace fastron::experiments {

CspaceResults runCspace(const CspaceOptions& o, const Progress& progress) {
  CspaceResults r;
  r.summary.columns = {"environment", "method", "grid_accuracy", "support"};
  r.grid.columns = {"environment", "x1", "x2", "truth", "Fastron", "ISVM", "SSVM"};
  r.support.columns = {"environment", "method", "x1", "x2", "weight"};
  r.cubes.columns = {"environment", "x", "y", "z", "side", "yaw"};
  const Robot rod = loadRobot("rod2");
  const JointLimits limits = rod.limits();
  const std::size_t n = o.quick ? 300 : 2000;
  const int resolution = o.quick ? 40 : 150;
  const double gamma = 30;  // the paper's 2-DOF settings (Sec. IV-A)

  // Grid in input space [-1, 1]^2 (the paper's axes), as joint configurations.
  Configurations grid(resolution * resolution, 2);
  for (int a = 0; a < resolution; ++a) {
    for (int b = 0; b < resolution; ++b) {
      grid.row(a * resolution + b) << -1 + 2.0 * a / (resolution - 1),
          -1 + 2.0 * b / (resolution - 1);
    }
  }
  const Configurations gridJoints = limits.toJoint(grid);

  for (std::size_t e = 0; e < o.environments; ++e) {
    if (progress)
      progress("cspace: environment " + std::to_string(e + 1) + "/" +
               std::to_string(o.environments));
    Rng rng(o.seed * 1000 + e);
    const Scene scene = randomCubes(4, 0.15, 0.30, 0.5, rng);
    const auto fcl = makeSceneChecker("fcl", rod, scene);
    const Labels truth = labelConfigurations(*fcl, gridJoints);
    const Configurations q = uniformConfigurations(limits, n, rng);
    const Labels y = labelConfigurations(*fcl, q);

    FastronClassifier fastron(limits, {.kernel = {KernelType::RationalQuadratic, gamma},
                                       .maxIterations = 1'000'000,
                                       .maxSupportPoints = n});
    fastron.train(q, y);
    IsvmClassifier isvm(
        limits, {KernelType::Gaussian, gamma},
        {.C = 10, .initialPoints = n / 10, .maxAdded = n - n / 10, .batch = n / 20, .seed = rng()});
    isvm.trainActively([&](const Configurations& a) { return labelConfigurations(*fcl, a); });
    SsvmClassifier ssvm(limits, {KernelType::RationalQuadratic, gamma}, {.C = 10});
    ssvm.train(q, y);

    const std::string env = std::to_string(e);
    const std::vector<const Classifier*> methods{&fastron, &isvm, &ssvm};
    std::vector<std::size_t> correct(methods.size(), 0);
    for (Eigen::Index i = 0; i < grid.rows(); ++i) {
      std::vector<std::string> row{env, cell(grid(i, 0)), cell(grid(i, 1)),
                                   std::to_string(truth[static_cast<std::size_t>(i)] > 0)};
      for (std::size_t m = 0; m < methods.size(); ++m) {
        const double score = methods[m]->score(gridJoints.row(i).data());
        correct[m] += (score > 0) == (truth[static_cast<std::size_t>(i)] > 0);
        row.push_back(cell(score));
      }
      r.grid.add(std::move(row));
    }
    // Support points, in input space, with the sign of their weight.
    auto addSupport = [&](const std::string& method, const Model& model) {
      for (Eigen::Index i = 0; i < model.supportFeatures().rows(); ++i) {
        r.support.add({env, method, cell(model.supportFeatures()(i, 0)),
                       cell(model.supportFeatures()(i, 1)), cell(model.weights()[i])});
      }
    };
    addSupport("Fastron", *fastron.model());
    addSupport("ISVM", *isvm.svm().expansion(limits).terms);
    addSupport("SSVM", *ssvm.expansion().terms);
    for (std::size_t m = 0; m < methods.size(); ++m) {
      r.summary.add({env, methods[m]->name(),
                     cell(static_cast<double>(correct[m]) / static_cast<double>(grid.rows())),
                     std::to_string(methods[m]->supportCount())});
    }
    for (const Obstacle& c : scene.obstacles()) {
      const Eigen::Vector3d p = c.pose.translation();
      r.cubes.add({env, cell(p.x()), cell(p.y()), cell(p.z()),
                   cell(std::get<Box>(c.shape).size.x()),
                   cell(std::atan2(c.pose.linear()(1, 0), c.pose.linear()(0, 0)))});
    }
  }
  return r;
}

std::string cspaceReport(const CspaceResults& r, const CspaceOptions& o) {
  std::ostringstream md;
  md << "# C-spaces of the 2-DOF rod (paper, Fig. 7)\n\n"
     << o.environments << " random environments of up to 4 cubes, seed " << o.seed
     << (o.quick ? ", quick mode" : "")
     << ". Each model is trained as in the static experiment (N = " << (o.quick ? 300 : 2000)
     << ", gamma = 30); accuracy on the whole grid of `cspace.png` against FCL.\n\n"
     << "| environment | method | grid accuracy | support points |\n|---|---|---|---|\n";
  for (const auto& row : r.summary.rows) {
    char accuracy[32];
    std::snprintf(accuracy, sizeof accuracy, "%.3f", std::stod(row[2]));
    md << "| " << row[0] << " | " << row[1] << " | " << accuracy << " | " << row[3] << " |\n";
  }
  return md.str();
}

}  // namespace fastron::experiments
