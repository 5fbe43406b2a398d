#include "fastron/geometry/control_points.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/kinematics.h"

namespace fastron {
namespace {

constexpr std::size_t kSampleCount = 64;  // configurations the automatic choice looks at
constexpr double kStaticTolerance = 1e-3;

/// Rotation taking the z axis onto the unit vector `axis`.
Eigen::Matrix3d alignZWith(const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
}

/// The transform a joint adds at a fixed value: origin, then its motion.
Eigen::Isometry3d jointTransform(const Joint& joint, double value) {
  Eigen::Isometry3d t = joint.origin;
  if (joint.type == JointType::Revolute || joint.type == JointType::Continuous) {
    t.rotate(Eigen::AngleAxisd(value, joint.axis));
  } else if (joint.type == JointType::Prismatic) {
    t.translate(value * joint.axis);
  }
  return t;
}

/// Axis-aligned box, in the link's frame, around the link's collision shapes; empty when the link
/// has none.
Eigen::AlignedBox3d linkBounds(const Robot& robot, int link) {
  Eigen::AlignedBox3d bounds;
  for (const LinkShape& s : robot.shapes()) {
    if (s.link != link) continue;
    const Eigen::Vector3d half = std::visit(
        [](const auto& shape) -> Eigen::Vector3d {
          using T = std::decay_t<decltype(shape)>;
          if constexpr (std::is_same_v<T, Box>) return shape.size / 2;
          if constexpr (std::is_same_v<T, Sphere>) return Eigen::Vector3d::Constant(shape.radius);
          if constexpr (std::is_same_v<T, Cylinder>) {
            return {shape.radius, shape.radius, shape.length / 2};
          }
          if constexpr (std::is_same_v<T, Capsule>) {
            return {shape.radius, shape.radius, shape.length / 2 + shape.radius};
          }
          if constexpr (std::is_same_v<T, Mesh>) {
            Eigen::Vector3d h = Eigen::Vector3d::Zero();
            for (const auto& v : shape.mesh->vertices) h = h.cwiseMax(v.cwiseAbs());
            return h;
          }
        },
        s.shape);
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d c((corner & 1) ? half.x() : -half.x(),
                              (corner & 2) ? half.y() : -half.y(),
                              (corner & 4) ? half.z() : -half.z());
      bounds.extend(s.origin * c);
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
  ControlPoint point;
  std::vector<Eigen::Vector3d> samples;  // world position at each sampled configuration
  double spread = 0;                     // RMS distance from the mean position
};

std::vector<Candidate> candidatePoints(const Robot& robot) {
  std::vector<Candidate> candidates;
  const auto& links = robot.links();
  for (std::size_t l = 0; l < links.size(); ++l) {
    candidates.push_back({{links[l].name, Eigen::Vector3d::Zero()}, {}, 0});
  }
  for (std::size_t l = 0; l < links.size(); ++l) {
    const Eigen::AlignedBox3d bounds = linkBounds(robot, static_cast<int>(l));
    if (bounds.isEmpty()) continue;
    bool hasMovingDescendant = false;
    for (const Joint& joint : robot.joints()) {
      if (joint.movable() && joint.child != static_cast<int>(l) &&
          isAncestor(robot, static_cast<int>(l), joint.child)) {
        hasMovingDescendant = true;
      }
    }
    if (!hasMovingDescendant) candidates.push_back({{links[l].name, farEnd(bounds)}, {}, 0});
  }
  return candidates;
}

void place(const Robot& robot, std::vector<Candidate>& candidates) {
  Rng rng(1);
  const Configurations q = uniformConfigurations(robot.limits(), kSampleCount, rng);
  KinematicsData data = makeKinematicsData(robot);
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    forwardKinematics(robot, q.row(i).data(), data);
    for (Candidate& c : candidates) {
      const auto link = static_cast<std::size_t>(robot.linkIndex(c.point.link));
      c.samples.push_back(data.linkPoses[link] * c.point.offset);
    }
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

void hashBytes(std::uint64_t& h, const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
}
void hashString(std::uint64_t& h, const std::string& s) {
  hashBytes(h, s.data(), s.size());
  hashBytes(h, "\0", 1);
}
void hashDoubles(std::uint64_t& h, const double* v, std::size_t n) {
  hashBytes(h, v, n * sizeof(double));
}

}  // namespace

std::vector<ControlPoint> defaultControlPoints(const Robot& robot,
                                               const ControlPointOptions& options) {
  if (!(options.minSpacing >= 0) || !std::isfinite(options.minSpacing)) {
    throw InvalidArgument("control point spacing must be finite and >= 0, got " +
                          std::to_string(options.minSpacing));
  }
  std::vector<Candidate> candidates = candidatePoints(robot);
  place(robot, candidates);
  std::erase_if(candidates, [](const Candidate& c) { return c.spread < kStaticTolerance; });
  // Most movement first; the stable sort keeps tree order (parents first) among equals.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.spread > b.spread; });
  std::vector<const Candidate*> chosen;
  for (const Candidate& c : candidates) {
    if (options.maxPoints > 0 && chosen.size() == options.maxPoints) break;
    const bool tooClose = std::any_of(chosen.begin(), chosen.end(), [&](const Candidate* other) {
      return meanDistance(c, *other) < std::max(options.minSpacing, kStaticTolerance);
    });
    if (!tooClose) chosen.push_back(&c);
  }
  if (chosen.empty()) {
    throw InvalidArgument(
        "robot '" + robot.name() +
        "': no link moves under the actuated joints, so there is no control point");
  }
  std::vector<ControlPoint> points;
  for (const Candidate* c : chosen) points.push_back(c->point);
  return points;
}

std::vector<ControlPoint> linkOriginPoints(const Robot& robot,
                                           const std::vector<std::string>& links) {
  std::vector<ControlPoint> points;
  for (const auto& link : links) {
    robot.linkIndex(link);  // throws naming an unknown link
    points.push_back({link, Eigen::Vector3d::Zero()});
  }
  return points;
}

std::uint64_t kinematicsChecksum(const Robot& robot) {
  std::uint64_t h = 14695981039346656037ULL;
  hashString(h, robot.name());
  for (const Link& link : robot.links()) hashString(h, link.name);
  for (std::size_t j = 0; j < robot.joints().size(); ++j) {
    const Joint& joint = robot.joints()[j];
    hashString(h, joint.name);
    const std::array<int, 3> ints{static_cast<int>(joint.type), joint.parent, joint.child};
    hashBytes(h, ints.data(), sizeof(ints));
    hashDoubles(h, joint.origin.matrix().data(), 16);
    hashDoubles(h, joint.axis.data(), 3);
    const double held = robot.heldPosition(static_cast<int>(j));
    hashDoubles(h, &held, 1);
  }
  for (const int a : robot.actuatedJoints()) hashBytes(h, &a, sizeof(a));
  return h;
}

RobotPointKinematics::RobotPointKinematics(const Robot& robot, std::vector<ControlPoint> points)
    : dof_(robot.dof()) {
  if (points.empty())
    throw InvalidArgument("robot '" + robot.name() + "': no control points given");
  const auto& joints = robot.joints();
  const auto& actuated = robot.actuatedJoints();
  // Each link's frame as (step, constant transform from that step's frame): fixed and held
  // joints are folded into the transform; an actuated joint starts a new step whose frame is the
  // child's frame turned so that the joint axis is its z axis.
  const std::size_t linkCount = robot.links().size();
  std::vector<int> stepOf(linkCount, -1);
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> inStep(
      linkCount, Eigen::Isometry3d::Identity());
  std::vector<Step> all;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const Joint& joint = joints[j];
    const auto parent = static_cast<std::size_t>(joint.parent);
    const auto child = static_cast<std::size_t>(joint.child);
    const auto position = std::find(actuated.begin(), actuated.end(), static_cast<int>(j));
    if (position == actuated.end()) {
      stepOf[child] = stepOf[parent];
      inStep[child] =
          inStep[parent] * jointTransform(joint, robot.heldPosition(static_cast<int>(j)));
      continue;
    }
    const Eigen::Matrix3d align = alignZWith(joint.axis);
    const Eigen::Isometry3d fixed = inStep[parent] * joint.origin;
    Step step;
    step.parent = stepOf[parent];
    step.joint = static_cast<int>(position - actuated.begin());
    step.prismatic = joint.type == JointType::Prismatic;
    step.rotation = fixed.linear() * align;
    step.translation = fixed.translation();
    stepOf[child] = static_cast<int>(all.size());
    inStep[child].setIdentity();
    inStep[child].linear() = align.transpose();
    all.push_back(step);
  }

  // Keep the steps some point hangs off, directly or through its parents, in order.
  std::vector<char> used(all.size(), 0);
  for (const ControlPoint& p : points) {
    for (int s = stepOf[static_cast<std::size_t>(robot.linkIndex(p.link))]; s >= 0;
         s = all[static_cast<std::size_t>(s)].parent) {
      used[static_cast<std::size_t>(s)] = 1;
    }
  }
  std::vector<int> newIndex(all.size(), -1);
  for (std::size_t s = 0; s < all.size(); ++s) {
    if (!used[s]) continue;
    Step step = all[s];
    if (step.parent >= 0) step.parent = newIndex[static_cast<std::size_t>(step.parent)];
    newIndex[s] = static_cast<int>(steps_.size());
    steps_.push_back(step);
  }
  if (steps_.size() > kMaxKinematicSteps) {
    throw InvalidArgument("robot '" + robot.name() + "': " + std::to_string(steps_.size()) +
                          " actuated joints lead to the control points, at most " +
                          std::to_string(kMaxKinematicSteps) + " are supported");
  }
  for (const ControlPoint& p : points) {
    const auto link = static_cast<std::size_t>(robot.linkIndex(p.link));
    const int step = stepOf[link] < 0 ? -1 : newIndex[static_cast<std::size_t>(stepOf[link])];
    points_.push_back({step, inStep[link] * p.offset});
  }

  description_.robot = robot.name();
  description_.joints = robot.actuatedJointNames();
  description_.points = std::move(points);
  description_.checksum = kinematicsChecksum(robot);
}

template <class T>
void RobotPointKinematics::place(const double* q, T* out) const {
  using Matrix3 = Eigen::Matrix<T, 3, 3>;
  using Vector3 = Eigen::Matrix<T, 3, 1>;
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): filled step by step
  std::array<Matrix3, kMaxKinematicSteps> rotations;
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): filled step by step
  std::array<Vector3, kMaxKinematicSteps> translations;
  for (std::size_t s = 0; s < steps_.size(); ++s) {
    const Step& step = steps_[s];
    Matrix3 r = step.rotation.cast<T>();
    Vector3 t = step.translation.cast<T>();
    if (step.parent >= 0) {
      const auto p = static_cast<std::size_t>(step.parent);
      t = rotations[p] * t + translations[p];
      r = rotations[p] * r;
    }
    const double value = q[step.joint];
    if (step.prismatic) {
      t += static_cast<T>(value) * r.col(2);
    } else {  // r * Rz(value): only the x and y columns turn
      const T c = static_cast<T>(std::cos(value));
      const T s = static_cast<T>(std::sin(value));
      const Vector3 x = r.col(0);
      r.col(0) = c * x + s * r.col(1);
      r.col(1) = c * r.col(1) - s * x;
    }
    rotations[s] = r;
    translations[s] = t;
  }
  for (std::size_t k = 0; k < points_.size(); ++k) {
    const Point& p = points_[k];
    Eigen::Map<Vector3> position(out + 3 * k);
    if (p.step < 0) {
      position = p.local.cast<T>();
    } else {
      const auto s = static_cast<std::size_t>(p.step);
      position = rotations[s] * p.local.cast<T>() + translations[s];
    }
  }
}

void RobotPointKinematics::positions(const double* q, double* out) const {
  place(q, out);
}
void RobotPointKinematics::positions(const double* q, float* out) const {
  place(q, out);
}

FeatureMap robotFeatures(const Robot& robot, FeatureKind kind, std::vector<ControlPoint> points,
                         double scale) {
  if (kind == FeatureKind::JointScaling) return FeatureMap::jointScaling(robot.limits());
  if (points.empty()) points = defaultControlPoints(robot);
  return FeatureMap::kinematic(
      robot.limits(), std::make_shared<RobotPointKinematics>(robot, std::move(points)), scale);
}

}  // namespace fastron
