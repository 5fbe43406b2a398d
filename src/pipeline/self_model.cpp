#include "fastron/pipeline/self_model.h"

#include <unistd.h>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "cache_key.h"
#include "fastron/core/error.h"
#include "fastron/core/model_checker.h"
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

constexpr double kTurn = 2 * std::numbers::pi;

/// A self-collision model whose coordinates `wrapped` are angles it learned on [-pi, pi]: each is
/// wrapped onto that turn before the model answers.
class TurnWrappingChecker final : public CollisionChecker {
  static constexpr std::size_t kBlock = 16;

 public:
  TurnWrappingChecker(std::shared_ptr<const Model> model, std::vector<std::size_t> wrapped,
                      std::string name)
      : model_(std::move(model)), wrapped_(std::move(wrapped)), name_(std::move(name)) {}
  std::string name() const override { return name_; }
  std::size_t dof() const override { return model_->dim(); }
  bool answersFromAModel() const override { return true; }

 protected:
  bool check(const double* q) const override { return checkFirst(q, 1) == 0; }
  /// A planner's edge wrapped a block of states at a time, each block answered by the model's
  /// batched path (as ModelChecker answers one).
  std::size_t checkFirst(const double* q, std::size_t n) const override {
    const std::size_t d = model_->dim();  // a joint-scaling model's: <= kMaxFeatureDimension
    std::array<double, kBlock * kMaxFeatureDimension> onOneTurn;
    for (std::size_t first = 0; first < n; first += kBlock) {
      const std::size_t rows = std::min(kBlock, n - first);
      std::copy(q + first * d, q + (first + rows) * d, onOneTurn.begin());
      for (std::size_t r = 0; r < rows; ++r) {
        for (const std::size_t i : wrapped_)
          onOneTurn[r * d + i] = std::remainder(onOneTurn[r * d + i], kTurn);
      }
      const std::size_t hit = model_->firstInCollision(onOneTurn.data(), rows);
      if (hit < rows) return first + hit;
    }
    return n;
  }

 private:
  std::shared_ptr<const Model> model_;
  std::vector<std::size_t> wrapped_;
  std::string name_;
};

/// The cached model, or none when the file is absent or does not fit the robot (a file of
/// another version, cut short, or of other limits).
std::shared_ptr<const Model> readCached(const std::filesystem::path& file, const Robot& robot) {
  if (!std::filesystem::is_regular_file(file)) return nullptr;
  try {
    auto model = std::make_shared<const Model>(loadModel(file));
    const JointLimits limits = selfModelLimits(robot);
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

JointLimits selfModelLimits(const Robot& robot) {
  const JointLimits limits = robot.limits();
  Eigen::VectorXd lower = limits.lower(), upper = limits.upper();
  for (const std::size_t i : coordinatesOfMoreThanATurn(robot)) {
    lower[static_cast<Eigen::Index>(i)] = -std::numbers::pi;
    upper[static_cast<Eigen::Index>(i)] = std::numbers::pi;
  }
  return JointLimits(lower, upper);
}

std::shared_ptr<const CollisionChecker> selfModelChecker(const Robot& robot,
                                                         std::shared_ptr<const Model> model,
                                                         std::string name) {
  if (!model) throw InvalidArgument("selfModelChecker: no model");
  if (model->dim() != robot.dof()) {
    throw InvalidArgument("selfModelChecker: a model of " + std::to_string(model->dim()) +
                          " joints for robot '" + robot.name() + "' of " +
                          std::to_string(robot.dof()));
  }
  // The coordinates the model learned on one turn (a model of the robot's own limits, none).
  const JointLimits& learned = model->limits();
  std::vector<std::size_t> wrapped;
  for (const std::size_t i : coordinatesOfMoreThanATurn(robot)) {
    const auto k = static_cast<Eigen::Index>(i);
    // As the file kept them: a model file's limits need not round-trip to the last bit.
    if (std::abs(learned.lower()[k] + std::numbers::pi) < 1e-9 &&
        std::abs(learned.upper()[k] - std::numbers::pi) < 1e-9)
      wrapped.push_back(i);
  }
  if (wrapped.empty())
    return std::make_shared<const ModelChecker>(std::move(model), std::move(name));
  return std::make_shared<const TurnWrappingChecker>(std::move(model), std::move(wrapped),
                                                     std::move(name));
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
      robotFeatures(robot, FeatureKind::JointScaling, selfModelLimits(robot)),
      selfModelParams(options.seed));
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
