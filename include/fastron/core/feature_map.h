#pragma once
// The model's input map: from a configuration (joint values) to the features the kernel compares.
//
// Two kinds. Joint scaling is the paper's (Sec. II-G): q_in = (2 q - q_u - q_l) / (q_u - q_l).
// Kinematic features are the world positions of a few control points on the robot, the input of
// the authors' forward-kinematics kernel (Das and Yip, RA-L 2020): two configurations are near
// when the robot's body is near, which in 7 joints is far more accurate with far fewer support
// points. `core` knows no robot: kinematic features reach it through PointKinematics, which the
// geometry layer implements.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/joint_limits.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

/// A point fixed in a link's frame whose world position is a feature.
struct ControlPoint {
  std::string link;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< in the link's frame, metres

  bool operator==(const ControlPoint&) const = default;
};

/// What a model file records of the kinematics behind its features, to refuse a robot that differs.
struct KinematicsDescription {
  std::string robot;
  std::vector<std::string> joints;  ///< actuated joints, in configuration order
  std::vector<ControlPoint> points;
  std::uint64_t checksum = 0;  ///< of the kinematic description (joint origins, axes, types)

  bool operator==(const KinematicsDescription&) const = default;
};

/// World positions of control points as a function of the configuration. Implementations are
/// immutable and thread-safe; positions() does not allocate.
class PointKinematics {
 public:
  virtual ~PointKinematics() = default;
  virtual std::size_t dof() const = 0;
  virtual std::size_t pointCount() const = 0;
  /// Writes 3 * pointCount() coordinates (x, y, z of each point, metres) for dof() joint values.
  virtual void positions(const double* q, double* out) const = 0;
  /// Float version of positions() for the query path; may be computed in float.
  virtual void positions(const double* q, float* out) const = 0;
  /// Float positions of n configurations, q row by row (n * dof() values), out row by row
  /// (n * 3 * pointCount()): the path for batches of queries such as edge checks. The default
  /// places them one by one; an implementation may compute many at once.
  virtual void positionsBatch(const double* q, std::size_t n, float* out) const;
  /// positions() in double, and their Jacobian with respect to the joint values: `jacobian`
  /// receives 3 * pointCount() rows of dof() values, row by row (d position / d q). The default
  /// takes central differences (step 1e-6); an implementation may compute it analytically.
  virtual void jacobian(const double* q, double* out, double* jacobian) const;
  virtual KinematicsDescription description() const = 0;
};

enum class FeatureKind : std::uint8_t {
  JointScaling = 0,  ///< joint values scaled to [-1, 1] by the joint limits
  Kinematic = 1,     ///< world positions of control points, in metres
};
std::string_view toString(FeatureKind kind);
/// "joints" or "fk"; throws InvalidArgument naming the value.
FeatureKind parseFeatureKind(std::string_view name);

/// Largest feature dimension a model accepts (queries keep their features on the stack).
inline constexpr std::size_t kMaxFeatureDimension = 192;

/// A value: cheap to copy (the kinematics are shared, immutable). Always holds the joint limits,
/// which bound sampling (uniform and active-learning samples are drawn in scaled joint space).
class FeatureMap {
 public:
  FeatureMap() = default;
  static FeatureMap jointScaling(JointLimits limits);
  /// Features = world positions of the kinematics' control points, in metres. (No scale factor:
  /// scaling every feature by s is the same model as the kernel's gamma times s^2.) Throws
  /// InvalidArgument when the kinematics are null, their dof differs from the limits, or they have
  /// no point or too many.
  static FeatureMap kinematic(JointLimits limits,
                              std::shared_ptr<const PointKinematics> kinematics);

  FeatureKind kind() const { return kind_; }
  const JointLimits& limits() const { return limits_; }
  /// Joint values per configuration.
  std::size_t configurationDim() const { return limits_.dim(); }
  /// Features per configuration.
  std::size_t featureDim() const { return featureDim_; }
  /// Null for joint scaling.
  const std::shared_ptr<const PointKinematics>& kinematics() const { return kinematics_; }

  /// Features of one configuration; q holds configurationDim() finite values (not checked: the
  /// hot path). `x` receives featureDim() values.
  void map(const double* q, double* x) const;
  void map(const double* q, float* x) const;
  /// Float features of n configurations, q and x row by row (not checked: the hot path).
  void mapBatch(const double* q, std::size_t n, float* x) const;
  /// Features of one configuration in double, and their Jacobian with respect to the joint
  /// values: `jacobian` receives featureDim() rows of configurationDim() values, row by row (not
  /// checked). Joint scaling: the diagonal of the scales; kinematic: the points' Jacobian.
  void jacobian(const double* q, double* x, double* jacobian) const;
  /// Throws InvalidArgument on a wrong column count or a non-finite value.
  void check(const Configurations& q) const;
  /// Features of every row, check()ed.
  Eigen::MatrixXd map(const Configurations& q) const;
  /// Features of the rows [begin, end) of q (not checked) into the same rows of x (featureDim()
  /// columns).
  void mapRows(const Configurations& q, Eigen::Index begin, Eigen::Index end,
               Eigen::MatrixXd& x) const;

  /// "joints" or "fk (N points)": for reports.
  std::string summary() const;

 private:
  template <class T>
  void mapTo(const double* q, T* x) const;

  FeatureKind kind_ = FeatureKind::JointScaling;
  JointLimits limits_;
  std::shared_ptr<const PointKinematics> kinematics_;
  std::size_t featureDim_ = 0;  // kept: the query path must not ask the kinematics each time
};

}  // namespace fastron
