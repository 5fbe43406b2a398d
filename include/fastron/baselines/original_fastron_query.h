#pragma once
// The query of the original Fastron C++ (Das and Yip's ucsdarclab/fastron, Fastron::eval),
// written anew as a baseline for query speed: what a user of that code gets per configuration.
//
// Its algorithm, reproduced: the support points are stored column by column in double; for each
// query, one Eigen array expression over them gives t = 2 / gamma + |s - x|^2 (the seven columns
// of a 7-D model in one pass, other dimensions one column at a time), and the score is
// sum alpha / t^2. That is the paper's rational-quadratic kernel scaled by (gamma / 2)^2 > 0, so
// its sign is Model::score's. It was built with -O3 and Eigen's default instructions (SSE2), as
// this library is; the original is a ROS package that needs MoveIt and Baxter's packages, not
// a Debian package, so it is not run itself (docs/performance.md, "Against the original
// Fastron's query").

#include <Eigen/Core>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/core/kernel.h"
#include "fastron/core/model.h"

namespace FASTRON_API fastron {

/// Immutable once built: queried from any number of threads (each query keeps its own array).
class OriginalFastronQuery {
 public:
  /// Copies the feature map, support features and weights of `model`. Throws InvalidArgument
  /// unless accepts(model.kernel()).
  explicit OriginalFastronQuery(const Model& model);

  /// Whether `kernel` is the original's: rational quadratic, one term over the whole vector.
  static bool accepts(const Kernel& kernel) {
    return kernel.type == KernelType::RationalQuadratic && kernel.block == 0;
  }

  /// The original's score of feature vector x (featureDim values): (gamma / 2)^2 f(x).
  double scoreFeatures(const double* x) const;
  /// q (dim joint values) mapped to features as the model maps them, then scored: true when
  /// the score is positive (the original's +1).
  bool inCollision(const double* q) const;

 private:
  FeatureMap features_;
  Eigen::MatrixXd support_;  // one support point per row, stored column by column
  Eigen::ArrayXd alpha_;
  double twoOverGamma_ = 0;
};

}  // namespace fastron
