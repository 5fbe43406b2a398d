#include "fastron/geometry/point_kinematics.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#ifdef __SSE2__
#include <immintrin.h>
#endif

#include "fastron/core/error.h"
#include "fastron/geometry/kinematics.h"
#include "internal/cephes_sin_cos.h"
#include "lane_kinematics.h"
#include "sin_cos.h"

namespace fastron {
namespace {

/// Rotation taking the z axis onto the unit vector `axis`.
Eigen::Matrix3d alignZWith(const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
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

/// A Frame (RobotPointKinematics' column-major rigid transform) from a rotation and a translation.
template <class Frame>
Frame toFrame(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation) {
  using T = typename decltype(Frame::m)::value_type;
  Frame f;
  f.m.fill(T(0));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) f(i, j) = static_cast<T>(rotation(i, j));
    f(i, 3) = static_cast<T>(translation[i]);
  }
  return f;
}

/// Below this magnitude a constant of the float chain is the rounding of a double computation
/// (cos(pi/2) is 6e-17, a URDF's rpy leaves 1e-17 in its rotations), not a length or a direction
/// (a nanometre, a billionth of a radian): the float chain takes it as 0. Left in, the products of
/// three of them along the chain are subnormal floats, which the processor handles slowly: the
/// mobile arm's positions took 95 ns instead of 72 (a 2-core AMD EPYC).
constexpr double kNegligibleConstant = 1e-9;

/// The float chain's copy of the double chain's constants `a`.
template <std::size_t N>
std::array<float, N> floatConstants(const std::array<double, N>& a) {
  std::array<float, N> out;
  for (std::size_t i = 0; i < N; ++i) {
    out[i] = std::abs(a[i]) < kNegligibleConstant ? 0.0f : static_cast<float>(a[i]);
  }
  return out;
}

/// Configurations handed to the lanes at once (a multiple of every path's register width).
constexpr std::size_t kConfigurationLanes = 16;
constexpr std::size_t kOneByOne = 2;  // batches this short are placed one configuration at a time

/// cos and sin of `count` angles, one by one (sin_cos.h): scalar code overlaps the chain of frames
/// (a SIMD sine and cosine of all angles first made it wait: 9-19 ns slower). Float features use
/// the Cephes polynomials of the lanes' sinCos, so the single chain and the batch compute the same
/// sines; double features (training, the exact score) those of the exact checkers' forward
/// kinematics. Baxter's 4 points on 20000 uniform configurations (a loop over FeatureMap::map)
/// took 95 ns with the C library's sinf and cosf and 65 ns with these; one configuration
/// repeated, as BM_ControlPoints does, took 61 and 65 ns and hid the difference.
template <class T>
void cosSin(const T* angles, std::size_t count, T* cosines, T* sines) {
  for (std::size_t k = 0; k < count; ++k) detail::sinCos(angles[k], sines[k], cosines[k]);
}

}  // namespace

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
  for (const MimicJoint& m :
       robot.mimicJoints()) {  // none on robots without mimics: old hashes hold
    hashBytes(h, &m.joint, sizeof(m.joint));
    hashBytes(h, &m.source, sizeof(m.source));
    hashDoubles(h, &m.multiplier, 1);
    hashDoubles(h, &m.offset, 1);
  }
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
  std::vector<Step<double>> all;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const Joint& joint = joints[j];
    const auto parent = static_cast<std::size_t>(joint.parent);
    const auto child = static_cast<std::size_t>(joint.child);
    // The configuration coordinate that turns the joint: its own, or its source's for a mimic.
    const auto mimic =
        std::find_if(robot.mimicJoints().begin(), robot.mimicJoints().end(),
                     [&](const MimicJoint& m) { return m.joint == static_cast<int>(j); });
    const bool mimics = mimic != robot.mimicJoints().end();
    const int driver = mimics ? mimic->source : static_cast<int>(j);
    const auto position = std::find(actuated.begin(), actuated.end(), driver);
    if (position == actuated.end()) {
      stepOf[child] = stepOf[parent];
      inStep[child] =
          inStep[parent] * jointTransform(joint, robot.heldPosition(static_cast<int>(j)));
      continue;
    }
    const Eigen::Matrix3d align = alignZWith(joint.axis);
    const Eigen::Isometry3d fixed = inStep[parent] * joint.origin;
    Step<double> step;
    step.parent = stepOf[parent];
    step.joint = static_cast<int>(position - actuated.begin());
    if (mimics) {
      step.scale = mimic->multiplier;
      step.offset = mimic->offset;
    }
    step.prismatic = joint.type == JointType::Prismatic;
    step.fixed = toFrame<Frame<double>>(fixed.linear() * align, fixed.translation());
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
    Step<double> step = all[s];
    if (step.parent >= 0) step.parent = newIndex[static_cast<std::size_t>(step.parent)];
    newIndex[s] = static_cast<int>(chain_.steps.size());
    chain_.steps.push_back(step);
  }
  if (chain_.steps.size() > kMaxKinematicSteps) {
    throw InvalidArgument("robot '" + robot.name() + "': " + std::to_string(chain_.steps.size()) +
                          " actuated joints lead to the control points, at most " +
                          std::to_string(kMaxKinematicSteps) + " are supported");
  }
  for (const ControlPoint& p : points) {
    const auto link = static_cast<std::size_t>(robot.linkIndex(p.link));
    const int step = stepOf[link] < 0 ? -1 : newIndex[static_cast<std::size_t>(stepOf[link])];
    const Eigen::Vector3d local = inStep[link] * p.offset;
    chain_.points.push_back({step, {local.x(), local.y(), local.z()}});
  }
  buildFloatChains();
  description_.robot = robot.name();
  description_.joints = robot.actuatedJointNames();
  description_.points = std::move(points);
  description_.checksum = kinematicsChecksum(robot);
}

void RobotPointKinematics::buildFloatChains() {
  for (const auto& step : chain_.steps) {
    chainF_.steps.push_back({step.parent,
                             step.joint,
                             static_cast<float>(step.scale),
                             static_cast<float>(step.offset),
                             step.prismatic,
                             {floatConstants(step.fixed.m)}});
  }
  for (const auto& point : chain_.points) {
    chainF_.points.push_back({point.step, floatConstants(point.local)});
  }
  for (const auto& step : chainF_.steps) {
    detail::LaneStep& lane = laneSteps_.emplace_back();
    lane.parent = step.parent;
    lane.joint = step.joint;
    lane.scale = step.scale;
    lane.offset = step.offset;
    lane.prismatic = step.prismatic ? 1 : 0;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 4; ++j) lane.fixed[4 * i + j] = step.fixed(i, j);
    }
  }
  for (const auto& point : chainF_.points) {
    detail::LanePoint& lane = lanePoints_.emplace_back();
    lane.step = point.step;
    for (std::size_t i = 0; i < 3; ++i) lane.local[i] = point.local[i];
  }
}

template <>
const RobotPointKinematics::Chain<double>& RobotPointKinematics::chain<double>() const {
  return chain_;
}
template <>
const RobotPointKinematics::Chain<float>& RobotPointKinematics::chain<float>() const {
  return chainF_;
}

namespace {

template <class T>
using FrameColumns = std::array<Eigen::Array<T, 4, 1>, 4>;  // x, y and z axes, then the origin

/// The world frame of every step of `c` at q (the chain's steps, in order).
template <class ChainT, class T>
void stepFrames(const ChainT& c, const double* q, FrameColumns<T>* frames) {
  using Column = Eigen::Array<T, 4, 1>;
  const std::size_t n = c.steps.size();
  // NOLINTBEGIN(cppcoreguidelines-pro-type-member-init): filled before they are read
  std::array<T, kMaxKinematicSteps> values, cosines, sines;
  // NOLINTEND(cppcoreguidelines-pro-type-member-init)
  for (std::size_t s = 0; s < n; ++s)
    values[s] = c.steps[s].scale * static_cast<T>(q[c.steps[s].joint]) + c.steps[s].offset;
  cosSin(values.data(), n, cosines.data(), sines.data());
  for (std::size_t s = 0; s < n; ++s) {
    const auto& step = c.steps[s];
    // The joint's motion is applied to the step's constant transform, not to the product with
    // the parent's frame: it does not wait for the parent, so the only work on the chain of
    // dependent products is one 3x4 product per step, column times broadcast scalar (with the
    // scalar sine and cosine, 1.7 times faster than the 12-scalar row-major frames that turned
    // the product: BM_ControlPoints).
    FrameColumns<T> g;
    for (int k = 0; k < 4; ++k) g[k] = Eigen::Map<const Column>(step.fixed.m.data() + 4 * k);
    if (step.prismatic) {
      g[3] += values[s] * g[2];
    } else {  // fixed * Rz(value): only the x and y axes turn
      const T co = cosines[s], si = sines[s];
      const Column x = g[0];
      g[0] = co * x + si * g[1];
      g[1] = co * g[1] - si * x;
    }
    FrameColumns<T>& f = frames[s];
    if (step.parent < 0) {
      f = g;
      continue;
    }
    const FrameColumns<T>& a = frames[static_cast<std::size_t>(step.parent)];
    for (int k = 0; k < 4; ++k) f[k] = a[0] * g[k][0] + a[1] * g[k][1] + a[2] * g[k][2];
    f[3] += a[3];
  }
}

/// A point's world position from its step's frame.
template <class PointT, class T>
Eigen::Array<T, 4, 1> pointPosition(const PointT& p, const FrameColumns<T>* frames) {
  if (p.step < 0) return {p.local[0], p.local[1], p.local[2], T(0)};
  const FrameColumns<T>& f = frames[static_cast<std::size_t>(p.step)];
  return f[0] * p.local[0] + f[1] * p.local[1] + f[2] * p.local[2] + f[3];
}

#ifdef __SSE2__
/// a * b + c, in one rounding where the build has FMA instructions.
inline __m128 mulAdd(__m128 a, __m128 b, __m128 c) {
#ifdef __FMA__
  return _mm_fmadd_ps(a, b, c);
#else
  return _mm_add_ps(_mm_mul_ps(a, b), c);
#endif
}
/// Lane `lane` of v in every lane (a shuffle within the register).
template <int lane>
__m128 splatLane(__m128 v) {
  return _mm_shuffle_ps(v, v, lane * 0x55);
}

/// A frame in registers: its x, y and z axes, then its origin.
struct RegisterFrame {
  __m128 column[4];  // NOLINT(modernize-avoid-c-arrays): std::array drops __m128's alignment
};

/// The float chain's positions (stepFrames and pointPosition for float) in SSE registers: the
/// step's turned transform stays in registers and lends its numbers to the product by shuffles.
/// Through Eigen's arrays the compiler stored it on the stack and broadcast each number back
/// from there: BM_ControlPoints<float> took 97 ns on Baxter (7 points) and 92 ns on the Panda
/// (4 points) that way, 81 and 74 ns this way (one run each, a 2-core AMD EPYC).
template <class ChainT>
void placeInRegisters(const ChainT& c, const double* q, float* out) {
  const std::size_t n = c.steps.size();
  // NOLINTBEGIN(cppcoreguidelines-pro-type-member-init): filled before they are read
  std::array<float, kMaxKinematicSteps> values, cosines, sines;
  std::array<RegisterFrame, kMaxKinematicSteps> frames;
  // NOLINTEND(cppcoreguidelines-pro-type-member-init)
  for (std::size_t s = 0; s < n; ++s)
    values[s] = c.steps[s].scale * static_cast<float>(q[c.steps[s].joint]) + c.steps[s].offset;
  cosSin(values.data(), n, cosines.data(), sines.data());
  for (std::size_t s = 0; s < n; ++s) {
    const auto& step = c.steps[s];
    RegisterFrame fixed;  // NOLINT(cppcoreguidelines-pro-type-member-init): loaded next
    __m128* g = fixed.column;
    for (std::size_t k = 0; k < 4; ++k) g[k] = _mm_loadu_ps(step.fixed.m.data() + 4 * k);
    if (step.prismatic) {
      g[3] = mulAdd(_mm_set1_ps(values[s]), g[2], g[3]);
    } else {  // fixed * Rz(value)
      const __m128 co = _mm_set1_ps(cosines[s]), si = _mm_set1_ps(sines[s]), x = g[0];
      g[0] = mulAdd(co, x, _mm_mul_ps(si, g[1]));
      g[1] = mulAdd(co, g[1], _mm_sub_ps(_mm_setzero_ps(), _mm_mul_ps(si, x)));
    }
    if (step.parent < 0) {
      frames[s] = fixed;
      continue;
    }
    __m128* f = frames[s].column;
    const __m128* a = frames[static_cast<std::size_t>(step.parent)].column;
    for (std::size_t k = 0; k < 4; ++k) {
      f[k] = mulAdd(a[0], splatLane<0>(g[k]),
                    mulAdd(a[1], splatLane<1>(g[k]), _mm_mul_ps(a[2], splatLane<2>(g[k]))));
    }
    f[3] = _mm_add_ps(f[3], a[3]);
  }
  for (std::size_t k = 0; k < c.points.size(); ++k) {
    const auto& p = c.points[k];
    alignas(16) std::array<float, 4> position{p.local[0], p.local[1], p.local[2], 0.0f};
    if (p.step >= 0) {
      const __m128* f = frames[static_cast<std::size_t>(p.step)].column;
      _mm_store_ps(position.data(), mulAdd(f[0], _mm_set1_ps(p.local[0]),
                                           mulAdd(f[1], _mm_set1_ps(p.local[1]),
                                                  mulAdd(f[2], _mm_set1_ps(p.local[2]), f[3]))));
    }
    std::copy_n(position.data(), 3, out + 3 * k);
  }
}
#endif

}  // namespace

template <class T>
void RobotPointKinematics::place(const double* q, T* out) const {
  const Chain<T>& c = chain<T>();
#ifdef __SSE2__
  if constexpr (std::is_same_v<T, float>) {
    placeInRegisters(c, q, out);
    return;
  }
#endif
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): filled before they are read
  std::array<FrameColumns<T>, kMaxKinematicSteps> frames;
  stepFrames(c, q, frames.data());
  for (std::size_t k = 0; k < c.points.size(); ++k)
    std::copy_n(pointPosition(c.points[k], frames.data()).data(), 3, out + 3 * k);
}

void RobotPointKinematics::jacobian(const double* q, double* out, double* jacobian) const {
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): filled before they are read
  std::array<FrameColumns<double>, kMaxKinematicSteps> frames;
  stepFrames(chain_, q, frames.data());
  std::fill_n(jacobian, 3 * chain_.points.size() * dof_, 0.0);
  for (std::size_t k = 0; k < chain_.points.size(); ++k) {
    const Eigen::Vector3d p = pointPosition(chain_.points[k], frames.data()).head<3>();
    std::copy_n(p.data(), 3, out + 3 * k);
    // Every step on the way to the point turns it about (or moves it along) the step's z axis,
    // which the step's own rotation leaves in place, through the step's origin.
    for (int s = chain_.points[k].step; s >= 0;
         s = chain_.steps[static_cast<std::size_t>(s)].parent) {
      const Step<double>& step = chain_.steps[static_cast<std::size_t>(s)];
      const FrameColumns<double>& f = frames[static_cast<std::size_t>(s)];
      const Eigen::Vector3d axis = f[2].head<3>();
      const Eigen::Vector3d moves =
          step.scale *
          (step.prismatic ? axis : Eigen::Vector3d(axis.cross(p - f[3].head<3>().matrix())));
      for (int a = 0; a < 3; ++a)
        jacobian[(3 * k + static_cast<std::size_t>(a)) * dof_ +
                 static_cast<std::size_t>(step.joint)] += moves[a];
    }
  }
}

void RobotPointKinematics::positionsBatch(const double* q, std::size_t n, float* out) const {
  const std::size_t coordinates = 3 * pointCount();
  for (std::size_t b = 0; b < n; b += kConfigurationLanes) {
    const std::size_t count = std::min(kConfigurationLanes, n - b);
    // A pass costs about the same however many lanes are used (AVX-512: 183 ns for four, 229 ns
    // for sixteen); one configuration is about 90 ns on the single chain (BM_ControlPoints,
    // BM_ControlPointsBatch): up to two go one by one.
    if (count <= kOneByOne) {
      for (std::size_t k = b; k < b + count; ++k) place(q + k * dof_, out + k * coordinates);
    } else {
      const detail::LaneChain chain{laneSteps_.data(), laneSteps_.size(), lanePoints_.data(),
                                    lanePoints_.size(), dof_};
      detail::activePlaceLanes()(chain, q + b * dof_, count, out + b * coordinates);
    }
  }
}

void RobotPointKinematics::positions(const double* q, double* out) const {
  place(q, out);
}
void RobotPointKinematics::positions(const double* q, float* out) const {
  place(q, out);
}

}  // namespace fastron
