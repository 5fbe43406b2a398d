#include "fastron/pipeline/self_model.h"

#include <unistd.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "cache_key.h"
#include "fastron/core/error.h"
#include "fastron/core/model_file.h"
#include "fastron/geometry/checker_options.h"
#include "fastron/geometry/point_kinematics.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/scene_checkers.h"
#include "fastron/pipeline/presets.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron::pipeline {
namespace {

/// The preset of the self-collision model: joint-space RQ kernel, gamma 5 and beta 500, no band
/// (docs/log/2026-11-25-a-self-collision-model-learned-once.md, "A self-collision model learned
/// once").
ProxyParams selfModelParams(std::uint64_t seed) {
  return withoutBand(robotProxyParams(5, 500, seed));
}

/// The cached model, or none when the file is absent or does not fit the robot (a file of
/// another version, cut short, or of other limits).
std::shared_ptr<const Model> readCached(const std::filesystem::path& file, const Robot& robot) {
  if (!std::filesystem::is_regular_file(file)) return nullptr;
  try {
    auto model = std::make_shared<const Model>(loadModel(file));
    const JointLimits limits = robot.limits();
    if (model->dim() != robot.dof() || model->features().kind() != FeatureKind::JointScaling ||
        !model->limits().lower().isApprox(limits.lower()) ||
        !model->limits().upper().isApprox(limits.upper()))
      return nullptr;
    return model;
  } catch (const Error&) {
    return nullptr;
  }
}

}  // namespace

std::filesystem::path defaultCacheDirectory() {
  if (const char* dir = std::getenv("FASTRON_CACHE_DIR"); dir != nullptr && *dir != '\0')
    return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != '\0')
    return std::filesystem::path(xdg) / "fastron";
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0')
    return std::filesystem::path(home) / ".cache" / "fastron";
  throw FileError(
      "no cache folder for self-collision models and self-pair tables: set FASTRON_CACHE_DIR (or "
      "XDG_CACHE_HOME or "
      "HOME)");
}

std::uint64_t selfModelKey(const Robot& robot, const SelfModelOptions& options) {
  Hash h;
  hashRobotCollisions(h, robot);
  h.value(options.samples);
  h.value(options.updates);
  h.value(options.seed);
  h.value(options.padding);
  return h.digest();
}

std::filesystem::path selfModelFile(const Robot& robot, const SelfModelOptions& options) {
  return cacheFile(options.cacheDirectory, robot, selfModelKey(robot, options), "fastron");
}

SelfModel selfCollisionModel(const Robot& robot, const SelfModelOptions& options) {
  SelfModel result;
  result.file = selfModelFile(robot, options);
  if ((result.model = readCached(result.file, robot))) {
    result.fromCache = true;
    return result;
  }
  ProxyCollisionDetector self(
      makeSceneChecker(kDefaultSceneChecker, robot, Scene{},
                       CheckerOptions{.selfCollision = true, .padding = options.padding}),
      robotFeatures(robot, FeatureKind::JointScaling), selfModelParams(options.seed));
  result.trainSeconds =
      std::chrono::duration<double>(trainStatic(self, options.samples, options.updates).total)
          .count();
  result.model = self.model();
  std::error_code error;
  std::filesystem::create_directories(result.file.parent_path(), error);
  if (error) {
    throw FileError(result.file.parent_path().string() +
                    ": cannot make the cache folder: " + error.message());
  }
  // A name of this process's own: two runs that train at once do not write one file.
  const std::filesystem::path partial =
      result.file.string() + "." + std::to_string(::getpid()) + ".part";
  saveModel(*result.model, partial);
  std::filesystem::rename(partial, result.file, error);
  if (error) {
    std::filesystem::remove(partial);
    throw FileError(result.file.string() + ": cannot write: " + error.message());
  }
  return result;
}

}  // namespace fastron::pipeline
