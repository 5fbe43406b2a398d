#include "fastron/geometry/scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "fastron/core/error.h"

namespace fastron {
namespace {

void validateMotion(const ObstacleMotion& motion, const std::string& where) {
  if (const auto* w = std::get_if<RandomWalk>(&motion)) {
    if (!std::isfinite(w->minStep) || !std::isfinite(w->maxStep) || w->minStep < 0 ||
        w->maxStep < w->minStep) {
      throw InvalidArgument(where + ": random walk needs 0 <= minStep <= maxStep");
    }
    if (w->bounds.isEmpty() || !w->bounds.min().allFinite() || !w->bounds.max().allFinite()) {
      throw InvalidArgument(where + ": random walk bounds are empty or not finite");
    }
  } else if (const auto* c = std::get_if<CircularPath>(&motion)) {
    if (!c->centre.allFinite() || !std::isfinite(c->radius) || c->radius < 0 ||
        !std::isfinite(c->period) || c->period <= 0 || !c->axis.allFinite() ||
        c->axis.norm() < 1e-12 || !std::isfinite(c->phase)) {
      throw InvalidArgument(
          where + ": circle needs a finite centre, radius >= 0, period > 0 and a nonzero axis");
    }
  } else if (const auto* s = std::get_if<ScriptedPoses>(&motion)) {
    if (s->times.empty() || s->times.size() != s->poses.size()) {
      throw InvalidArgument(where +
                            ": scripted motion needs one time per pose and at least one pose");
    }
    for (std::size_t i = 0; i < s->times.size(); ++i) {
      if (!std::isfinite(s->times[i]) || (i > 0 && s->times[i] <= s->times[i - 1])) {
        throw InvalidArgument(where + ": scripted times must be finite and increasing");
      }
      if (!s->poses[i].matrix().allFinite())
        throw InvalidArgument(where + ": scripted pose is not finite");
    }
  }
}

Eigen::Vector3d reflectInto(Eigen::Vector3d p, const Eigen::AlignedBox3d& box) {
  for (int k = 0; k < 3; ++k) {
    const double lo = box.min()[k], hi = box.max()[k];
    if (hi <= lo) {
      p[k] = lo;
      continue;
    }
    const double span = hi - lo;
    double offset = std::fmod(p[k] - lo, 2 * span);  // unfold repeated reflections
    if (offset < 0) offset += 2 * span;
    p[k] = lo + (offset <= span ? offset : 2 * span - offset);
  }
  return p;
}

}  // namespace

Scene Scene::grown(double margin) const {
  if (!std::isfinite(margin) || margin < 0) {
    throw InvalidArgument("an obstacle margin must be finite and >= 0, got " +
                          std::to_string(margin));
  }
  Scene result = *this;
  for (Obstacle& o : result.obstacles_) {
    if (!std::holds_alternative<Mesh>(o.shape)) o.shape = inflate(o.shape, margin);
  }
  return result;
}

Eigen::Isometry3d makePose(const Eigen::Vector3d& position, const Eigen::Vector3d& rpy) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = position;
  pose.linear() = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  return pose;
}

void Scene::add(Obstacle obstacle) {
  const std::string where = "obstacle '" + obstacle.name + "'";
  if (obstacle.name.empty()) throw InvalidArgument("an obstacle needs a name");
  for (const auto& o : obstacles_) {
    if (o.name == obstacle.name)
      throw InvalidArgument("two obstacles named '" + obstacle.name + "'");
  }
  validate(obstacle.shape, where);
  if (!obstacle.pose.matrix().allFinite()) throw InvalidArgument(where + ": pose is not finite");
  if (obstacle.motion) validateMotion(*obstacle.motion, where);
  const std::uint64_t seed = obstacle.motion && std::holds_alternative<RandomWalk>(*obstacle.motion)
                                 ? std::get<RandomWalk>(*obstacle.motion).seed
                                 : 0;
  obstacles_.push_back(std::move(obstacle));
  walkers_.emplace_back(seed);
  // Circles and scripts define the pose at every time, now included; a random walk starts from
  // the given pose.
  if (seed == 0) applyMotion(obstacles_.size() - 1);
}

std::size_t Scene::indexOf(std::string_view name) const {
  for (std::size_t i = 0; i < obstacles_.size(); ++i) {
    if (obstacles_[i].name == name) return i;
  }
  throw InvalidArgument("the scene has no obstacle '" + std::string(name) + "'");
}

void Scene::remove(std::string_view name) {
  const std::size_t i = indexOf(name);
  obstacles_.erase(obstacles_.begin() + static_cast<std::ptrdiff_t>(i));
  walkers_.erase(walkers_.begin() + static_cast<std::ptrdiff_t>(i));
}

void Scene::setPose(std::string_view name, const Eigen::Isometry3d& pose) {
  if (!pose.matrix().allFinite())
    throw InvalidArgument("obstacle '" + std::string(name) + "': pose is not finite");
  obstacles_[indexOf(name)].pose = pose;
}

void Scene::setShape(std::string_view name, Shape shape) {
  const std::size_t i = indexOf(name);
  validate(shape, "obstacle '" + std::string(name) + "'");
  obstacles_[i].shape = std::move(shape);
}

const Obstacle& Scene::obstacle(std::string_view name) const {
  return obstacles_[indexOf(name)];
}

void Scene::step(std::size_t steps) {
  for (std::size_t s = 0; s < steps; ++s) {
    time_ += 1;
    for (std::size_t i = 0; i < obstacles_.size(); ++i) applyMotion(i);
  }
}

void Scene::applyMotion(std::size_t i) {
  Obstacle& o = obstacles_[i];
  if (!o.motion) return;
  if (const auto* w = std::get_if<RandomWalk>(&*o.motion)) {
    Rng& rng = walkers_[i];
    std::normal_distribution<double> normal;
    Eigen::Vector3d direction(normal(rng), normal(rng), normal(rng));
    if (direction.norm() < 1e-12) direction = Eigen::Vector3d::UnitX();
    const double length = std::uniform_real_distribution<double>(w->minStep, w->maxStep)(rng);
    o.pose.translation() =
        reflectInto(o.pose.translation() + length * direction.normalized(), w->bounds);
  } else if (const auto* c = std::get_if<CircularPath>(&*o.motion)) {
    const Eigen::Vector3d axis = c->axis.normalized();
    const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
    const double angle = c->phase + 2 * std::numbers::pi * time_ / c->period;
    o.pose.translation() = c->centre + c->radius * (std::cos(angle) * u + std::sin(angle) * v);
  } else if (const auto* s = std::get_if<ScriptedPoses>(&*o.motion)) {
    const auto next = std::upper_bound(s->times.begin(), s->times.end(), time_);
    if (next == s->times.begin()) {
      o.pose = s->poses.front();
    } else if (next == s->times.end()) {
      o.pose = s->poses.back();
    } else {
      const auto k = static_cast<std::size_t>(next - s->times.begin());
      const double t = (time_ - s->times[k - 1]) / (s->times[k] - s->times[k - 1]);
      const Eigen::Isometry3d& a = s->poses[k - 1];
      const Eigen::Isometry3d& b = s->poses[k];
      o.pose.translation() = (1 - t) * a.translation() + t * b.translation();
      o.pose.linear() = Eigen::Quaterniond(a.linear())
                            .slerp(t, Eigen::Quaterniond(b.linear()))
                            .toRotationMatrix();
    }
  }
}

}  // namespace fastron
