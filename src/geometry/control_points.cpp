#include "fastron/geometry/control_points.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string_view>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/kinematics.h"

namespace fastron {
namespace {

constexpr std::size_t kSampleCount = 64;  // configurations the automatic choice looks at
constexpr double kStaticTolerance = 1e-3;

/// Axis-aligned box, in the link's frame, around the link's collision shapes (a mesh by its
/// vertices); empty when the link has none.
Eigen::AlignedBox3d linkBounds(const Robot& robot, int link) {
  Eigen::AlignedBox3d bounds;
  for (const LinkShape& s : robot.shapes()) {
    if (s.link != link) continue;
    const Eigen::AlignedBox3d own = shapeBounds(s.shape);
    if (own.isEmpty()) continue;
    for (int corner = 0; corner < 8; ++corner) {
      bounds.extend(s.origin * own.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner)));
    }
  }
  return bounds;
}

/// The centre of the face of `bounds` farthest from the link origin along its longest side.
Eigen::Vector3d farEnd(const Eigen::AlignedBox3d& bounds) {
  Eigen::Index axis = 0;
  bounds.sizes().maxCoeff(&axis);
  Eigen::Vector3d p = bounds.center();
  p[axis] = std::abs(bounds.max()[axis]) >= std::abs(bounds.min()[axis]) ? bounds.max()[axis]
                                                                         : bounds.min()[axis];
  return p;
}

/// Whether link `ancestor` lies on the path from the root to `link` (a link is its own ancestor).
bool isAncestor(const Robot& robot, int ancestor, int link) {
  while (link >= 0) {
    if (link == ancestor) return true;
    const int joint = robot.links()[static_cast<std::size_t>(link)].parentJoint;
    if (joint < 0) return false;
    link = robot.joints()[static_cast<std::size_t>(joint)].parent;
  }
  return false;
}

struct Candidate {
  std::size_t link = 0;
  std::size_t body = 0;  // the link that starts its rigid body (see rigidBodyOf)
  ControlPoint point;
  std::vector<Eigen::Vector3d> samples;  // world position at each sampled configuration
  double spread = 0;                     // RMS distance from the mean position
};

/// The link that starts `link`'s rigid body under the actuated joints: the nearest link, `link`
/// itself or an ancestor, whose parent joint is actuated (or the root). Links joined by fixed or
/// held joints share it.
std::size_t rigidBodyOf(const Robot& robot, std::size_t link) {
  for (;;) {
    const int joint = robot.links()[link].parentJoint;
    if (joint < 0 || robot.followsConfiguration(joint)) return link;
    link = static_cast<std::size_t>(robot.joints()[static_cast<std::size_t>(joint)].parent);
  }
}

/// The centres of the two faces of `bounds` at the ends of its longest side.
std::array<Eigen::Vector3d, 2> ends(const Eigen::AlignedBox3d& bounds) {
  Eigen::Index axis = 0;
  bounds.sizes().maxCoeff(&axis);
  std::array<Eigen::Vector3d, 2> out{bounds.center(), bounds.center()};
  out[0][axis] = bounds.min()[axis];
  out[1][axis] = bounds.max()[axis];
  return out;
}

std::vector<Candidate> candidatePoints(const Robot& robot, bool alongGeometry) {
  std::vector<Candidate> candidates;
  const auto& links = robot.links();
  const auto add = [&](std::size_t link, const Eigen::Vector3d& offset) {
    candidates.push_back({link, rigidBodyOf(robot, link), {links[link].name, offset}, {}, 0});
  };
  for (std::size_t l = 0; l < links.size(); ++l) add(l, Eigen::Vector3d::Zero());
  for (std::size_t l = 0; l < links.size(); ++l) {
    const Eigen::AlignedBox3d bounds = linkBounds(robot, static_cast<int>(l));
    if (bounds.isEmpty()) continue;
    // A movable joint below the link: its parent is the link or one of the link's descendants.
    const bool hasMovingDescendant =
        std::any_of(robot.joints().begin(), robot.joints().end(), [&](const Joint& joint) {
          return joint.movable() && isAncestor(robot, static_cast<int>(l), joint.parent);
        });
    if (!hasMovingDescendant) add(l, farEnd(bounds));
    if (alongGeometry) {
      add(l, bounds.center());
      for (const Eigen::Vector3d& end : ends(bounds)) add(l, end);
    }
  }
  return candidates;
}

void place(const Robot& robot, std::vector<Candidate>& candidates) {
  Rng rng(1);
  const Configurations q = uniformConfigurations(robot.limits(), kSampleCount, rng);
  KinematicsData data = makeKinematicsData(robot);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    forwardKinematics(robot, q.row(i).data(), data);
    for (Candidate& c : candidates) c.samples.push_back(data.linkPoses[c.link] * c.point.offset);
  }
  for (Candidate& c : candidates) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : c.samples) mean += p;
    mean /= static_cast<double>(c.samples.size());
    double sum = 0;
    for (const auto& p : c.samples) sum += (p - mean).squaredNorm();
    c.spread = std::sqrt(sum / static_cast<double>(c.samples.size()));
  }
}

double meanDistance(const Candidate& a, const Candidate& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.samples.size(); ++i) sum += (a.samples[i] - b.samples[i]).norm();
  return sum / static_cast<double>(a.samples.size());
}

/// Whether a rigid body holds options.maxPerBody chosen points already.
bool bodyFull(const std::vector<const Candidate*>& chosen, const Candidate& c,
              const ControlPointOptions& options) {
  const auto onBody = std::count_if(chosen.begin(), chosen.end(),
                                    [&](const Candidate* other) { return other->body == c.body; });
  return options.maxPerBody > 0 && static_cast<std::size_t>(onBody) >= options.maxPerBody;
}

/// ControlPointRule::Spread: most movement first; the stable sort keeps tree order (parents
/// first) among equals.
std::vector<const Candidate*> bySpread(std::vector<Candidate>& candidates,
                                       const ControlPointOptions& options) {
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.spread > b.spread; });
  std::vector<const Candidate*> chosen;
  for (const Candidate& c : candidates) {
    if (options.maxPoints > 0 && chosen.size() == options.maxPoints) break;
    const bool tooClose = std::any_of(chosen.begin(), chosen.end(), [&](const Candidate* other) {
      return meanDistance(c, *other) < std::max(options.minSpacing, kStaticTolerance);
    });
    if (!tooClose && !bodyFull(chosen, c, options)) chosen.push_back(&c);
  }
  return chosen;
}

/// ControlPointRule::Cover: the candidate that moves most, then each time the one least
/// explained by the points chosen (its mean distance to the nearest, capped by how much it moves
/// at all: a point that barely moves needs no point of its own).
std::vector<const Candidate*> byCover(const std::vector<Candidate>& candidates,
                                      const ControlPointOptions& options) {
  std::vector<const Candidate*> chosen;
  std::vector<double> uncovered;  // per candidate
  for (const Candidate& c : candidates) uncovered.push_back(c.spread);
  for (;;) {
    if (options.maxPoints > 0 && chosen.size() == options.maxPoints) break;
    std::size_t best = candidates.size();
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (bodyFull(chosen, candidates[i], options)) continue;
      // Ties keep tree order (parents first).
      if (best == candidates.size() || uncovered[i] > uncovered[best]) best = i;
    }
    if (best == candidates.size() ||
        (!chosen.empty() && uncovered[best] < std::max(options.minSpacing, kStaticTolerance)))
      break;
    chosen.push_back(&candidates[best]);
    for (std::size_t i = 0; i < candidates.size(); ++i)
      uncovered[i] = std::min(uncovered[i], meanDistance(candidates[i], candidates[best]));
  }
  return chosen;
}

}  // namespace

std::vector<ControlPoint> defaultControlPoints(const Robot& robot,
                                               const ControlPointOptions& options) {
  if (!(options.minSpacing >= 0) || !std::isfinite(options.minSpacing)) {
    throw InvalidArgument("control point spacing must be finite and >= 0, got " +
                          std::to_string(options.minSpacing));
  }
  std::vector<Candidate> candidates = candidatePoints(robot, options.alongGeometry);
  place(robot, candidates);
  std::erase_if(candidates, [](const Candidate& c) { return c.spread < kStaticTolerance; });
  const std::vector<const Candidate*> chosen = options.rule == ControlPointRule::Spread
                                                   ? bySpread(candidates, options)
                                                   : byCover(candidates, options);
  if (chosen.empty()) {
    throw InvalidArgument(
        "robot '" + robot.name() +
        "': no link moves under the actuated joints, so there is no control point");
  }
  std::vector<ControlPoint> points;
  for (const Candidate* c : chosen) points.push_back(c->point);
  return points;
}

std::vector<ControlPoint> namedControlPoints(const Robot& robot,
                                             const std::vector<std::string>& specs) {
  std::vector<ControlPoint> points;
  for (const std::string& spec : specs) {
    const std::size_t at = spec.find('@');
    ControlPoint point{spec.substr(0, at), Eigen::Vector3d::Zero()};
    robot.linkIndex(point.link);  // throws naming an unknown link
    if (at != std::string::npos) {
      const std::string_view offset = std::string_view(spec).substr(at + 1);
      std::size_t start = 0;
      for (int axis = 0; axis < 3; ++axis) {
        const std::size_t end = axis < 2 ? offset.find(':', start) : offset.size();
        const std::string_view field = end == std::string_view::npos
                                           ? offset.substr(start)
                                           : offset.substr(start, end - start);
        double value = 0.0;
        const auto [last, error] =
            std::from_chars(field.data(), field.data() + field.size(), value);
        if (end == std::string_view::npos || error != std::errc() ||
            last != field.data() + field.size() || field.empty() || !std::isfinite(value)) {
          throw InvalidArgument("control point '" + spec +
                                "': expected LINK or LINK@X:Y:Z (an offset in the link's frame, "
                                "metres, three finite numbers)");
        }
        point.offset[axis] = value;
        start = end + 1;
      }
    }
    points.push_back(std::move(point));
  }
  return points;
}

}  // namespace fastron
