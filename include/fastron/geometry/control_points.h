#pragma once
// Task-space features for a robot: control points on its links and the fast, positions-only
// forward kinematics that places them (the PointKinematics of core/feature_map.h).

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/core/model.h"
#include "fastron/geometry/detail/lane_chain.h"
#include "fastron/geometry/robot.h"

namespace FASTRON_API fastron {

/// How defaultControlPoints orders the candidates it takes.
enum class ControlPointRule {
  /// By how much they move, the points far down the chain first (measured on Baxter and the
  /// Panda: docs/algorithms.md).
  Spread,
  /// A greedy cover of the moving geometry: the point that moves most, then each time the one
  /// least explained by the points taken (its mean distance to the nearest of them, capped by how
  /// much it moves at all), so that the points spread along the chain (a hand, then an elbow, an
  /// upper arm) rather than crowd the hand. Measured on robots the spread rule was not tuned on:
  /// docs/algorithms.md, "Control points on robots of other makers".
  Cover,
};

/// How control points are chosen automatically (see defaultControlPoints).
struct ControlPointOptions {
  ControlPointRule rule = ControlPointRule::Spread;
  /// At most this many points (0 = every candidate left after the spacing rule). More points
  /// cost query time and, measured on Baxter and the Panda, do not buy accuracy (the points far
  /// down the chain are the ones that collide): docs/algorithms.md.
  std::size_t maxPoints = 4;
  /// A candidate closer than this (mean distance over sampled configurations, metres) to a point
  /// already chosen adds little and is skipped.
  double minSpacing = 0.1;
  /// At most this many points on one rigid body (links joined by fixed or held joints; 0 = no
  /// limit): three fix the body's pose, so a fourth adds nothing a kernel over positions can use,
  /// and without the limit the mesh Panda's large hand took every point and left the forearm
  /// unseen.
  std::size_t maxPerBody = 3;
};

/// The control points a task-space model of `robot` uses by default. Candidates are the origins
/// of the links that move under the actuated joints, and, for each link with collision geometry
/// but no moving descendant, the far end of its geometry (the centre of the face of its bounding
/// box farthest from the link origin along the longest side). The candidates are placed at 64
/// seeded random configurations; a candidate that stays within 1 mm of one place is dropped.
/// The rest are taken in the order of options.rule (Spread: how much they move, the standard
/// deviation of the position; Cover: see ControlPointRule), skipping one closer than
/// options.minSpacing on average to a point already taken or on a rigid body that has
/// options.maxPerBody points already, up to options.maxPoints. The result depends only on the
/// robot and the options.
std::vector<ControlPoint> defaultControlPoints(const Robot& robot,
                                               const ControlPointOptions& options = {});

/// Control points named by the user, in order: "LINK" is the link's origin, "LINK@X:Y:Z" the
/// point at offset (X, Y, Z) metres in the link's frame. Throws InvalidArgument naming an unknown
/// link or a malformed offset.
std::vector<ControlPoint> namedControlPoints(const Robot& robot,
                                             const std::vector<std::string>& specs);

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

  std::size_t dof_ = 0;
  Chain<double> chain_;
  Chain<float> chainF_;
  std::vector<detail::LaneStep> laneSteps_;  // chainF_ for the batched kinematics
  std::vector<detail::LanePoint> lanePoints_;
  KinematicsDescription description_;
};

/// Largest number of actuated joints between the base and a control point.
inline constexpr std::size_t kMaxKinematicSteps = detail::kMaxLaneSteps;

/// The model's features for `robot`: joint scaling by its limits, or the world positions of
/// `points` (defaultControlPoints when empty).
FeatureMap robotFeatures(const Robot& robot, FeatureKind kind,
                         std::vector<ControlPoint> points = {});
/// The same with other joint limits than the robot's (e.g. a narrower range to sample).
FeatureMap robotFeatures(const Robot& robot, FeatureKind kind, JointLimits limits,
                         std::vector<ControlPoint> points = {});

/// Loads a model file for `robot`: a task-space model gets kinematics built from `robot` and the
/// control points the file records, and is refused (FileError naming the difference) when the
/// robot's name, actuated joints or kinematics differ from those it was trained on.
Model loadModelFor(const std::filesystem::path& path, const Robot& robot);

}  // namespace fastron
