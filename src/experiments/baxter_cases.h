#pragma once
// The Baxter cases of the paper's changing-environment and planning experiments (Sec. IV-B and
// IV-C), shared by both. Internal to the experiments library.

#include <cstdint>
#include <string>

#include "fastron/core/error.h"

#include "fastron/geometry/robot.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/pipeline/presets.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron::experiments {

// The paper's settings (Sec. IV-B) for joint-space models: gamma 10 and beta 100 for 4 joints, 5
// and 500 above; 500 active-learning points per update. Task-space models take
// defaultProxyParams' (pipeline::robotProxyParams).
struct Case {
  std::size_t joints;
  std::string scene;
  double gamma, beta;
};

inline Case caseFor(const std::string& name) {
  if (name == "4dof") return {4, "baxter_one_box.yaml", 10, 100};
  if (name == "6dof") return {6, "baxter_one_box.yaml", 5, 500};
  if (name == "7dof") return {7, "baxter_one_box.yaml", 5, 500};
  if (name == "7dof-3boxes") return {7, "baxter_three_boxes.yaml", 5, 500};
  throw InvalidArgument("unknown changing-environment case '" + name +
                        "' (4dof, 6dof, 7dof, 7dof-3boxes)");
}

inline Robot baxterWithJoints(std::size_t joints) {
  Robot baxter = loadRobot("baxter");
  std::vector<std::string> names = baxter.actuatedJointNames();
  names.resize(joints);
  baxter.setActuatedJoints(names);
  return baxter;
}

// The shipped scene with every random walk reseeded for this trial.
inline Scene sceneForTrial(const std::string& file, std::uint64_t seed) {
  const Scene shipped = loadScene(dataDirectory() / "scenes" / file);
  Scene scene;
  scene.robotBase = shipped.robotBase;
  for (Obstacle o : shipped.obstacles()) {
    if (o.motion && std::holds_alternative<RandomWalk>(*o.motion))
      std::get<RandomWalk>(*o.motion).seed += seed * 7919;
    scene.add(std::move(o));
  }
  return scene;
}

inline ProxyParams proxyParams(const Case& c, std::uint64_t seed, FeatureKind kind) {
  return pipeline::robotProxyParams(kind, c.gamma, c.beta, seed);
}

}  // namespace fastron::experiments
