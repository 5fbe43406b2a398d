#pragma once
// The fast, positions-only forward kinematics that places a robot's control points (the
// PointKinematics of core/feature_map.h), and the checksum of what it depends on.

#include <array>
#include <cstdint>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/geometry/detail/lane_chain.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {

/// 64-bit FNV-1a hash of what the positions depend on: the links and joints in tree order with
/// their types, origins, axes and held positions, and the actuated joints.
std::uint64_t kinematicsChecksum(const Robot& robot);

/// World positions (in the robot's base frame) of control points. The robot's kinematic tree is
/// compiled once: fixed and held joints are folded into constant transforms, each actuated joint
/// on the way to a point becomes one rotation (or translation) about a local z axis, so a query
/// costs two 3x3 products per joint, and nothing is allocated.
class RobotPointKinematics final : public PointKinematics {
 public:
  /// Throws InvalidArgument for an unknown link or no points.
  RobotPointKinematics(const Robot& robot, std::vector<ControlPoint> points);

  std::size_t dof() const override { return dof_; }
  std::size_t pointCount() const override { return chain_.points.size(); }
  void positions(const double* q, double* out) const override;
  void positions(const double* q, float* out) const override;
  /// One configuration per SIMD lane (16 on AVX-512, 8 on AVX2, 4 on SSE2: simd.h): the frames of
  /// a step are computed for a register of them at once (structure of arrays), so a batch costs a
  /// fraction of single queries.
  void positionsBatch(const double* q, std::size_t n, float* out) const override;
  /// Analytic: each actuated step on a point's way contributes its z axis times the point's
  /// offset from the step's origin (a revolute joint) or its z axis (a prismatic one), times the
  /// coordinate's multiplier (mimic joints).
  void jacobian(const double* q, double* out, double* jacobian) const override;
  KinematicsDescription description() const override { return description_; }

  /// Actuated joints that move at least one control point.
  std::size_t steps() const { return chain_.steps.size(); }

 private:
  /// A rigid transform stored column by column: the x, y and z axes, then the origin, each
  /// padded to four numbers (the fourth 0) so that a column loads as one SIMD vector.
  template <class T>
  struct Frame {
    std::array<T, 16> m;
    T operator()(int row, int column) const {
      return m[static_cast<std::size_t>(4 * column + row)];
    }
    T& operator()(int row, int column) { return m[static_cast<std::size_t>(4 * column + row)]; }
  };
  /// One actuated joint: a constant transform from the parent step's frame, then a rotation
  /// about (or translation along) the local z axis by the joint's value.
  template <class T>
  struct Step {
    int parent = -1;          ///< step whose frame this one's hangs off, -1 for the base
    int joint = 0;            ///< index into the configuration
    T scale = 1, offset = 0;  ///< the joint's value: scale * that coordinate + offset (mimics)
    bool prismatic = false;
    Frame<T> fixed;
  };
  template <class T>
  struct Point {
    int step = -1;  ///< frame the point is fixed in, -1 for the base
    std::array<T, 3> local;
  };
  template <class T>
  struct Chain {
    std::vector<Step<T>> steps;
    std::vector<Point<T>> points;
  };
  /// The float chain for queries; the double one for training and exact scores.
  template <class T>
  const Chain<T>& chain() const;
  template <class T>
  void place(const double* q, T* out) const;
  /// The float chain and the lanes' plain copy of it, from the double chain.
  void buildFloatChains();

  std::size_t dof_ = 0;
  Chain<double> chain_;
  Chain<float> chainF_;
  std::vector<detail::LaneStep> laneSteps_;  // chainF_ for the batched kinematics
  std::vector<detail::LanePoint> lanePoints_;
  KinematicsDescription description_;
};

/// Largest number of actuated joints between the base and a control point.
inline constexpr std::size_t kMaxKinematicSteps = detail::kMaxLaneSteps;

}  // namespace fastron
