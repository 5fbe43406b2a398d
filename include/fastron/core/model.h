#pragma once
// The Fastron model: an immutable snapshot of a support set and its weights,
// f(x) = sum_i alpha_i k(s_i, x), with sign(f) as the proxy collision label (paper, Sec. II-A).

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <span>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/core/kernel.h"
#include "fastron/core/point_field.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {
namespace detail {
struct SupportView;

/// Allocates on 64-byte boundaries (a cache line, and an AVX-512 register), whatever
/// instruction set the including code is compiled for.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlignment)); }
  void deallocate(T* p, std::size_t /*n*/) { ::operator delete(p, kAlignment); }
  friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator&) { return true; }
};
}  // namespace detail

/// The largest magnitude of a feature or weight a model (and a Trainer) takes: queries sum in
/// float, where a larger value would be infinite (and 0 * inf = NaN in the kernel sum); the margin
/// below float's largest leaves room for sums of many of them.
inline constexpr double kMaxFloatValue = 1e30;

/// Immutable once built, so one instance can be queried from any number of threads; queries do
/// not allocate. Queries take joint values; the model maps them to its features itself (joint
/// scaling to [-1, 1]^d, or the world positions of control points: see feature_map.h).
///
/// Two evaluation paths are kept: `score` sums over a padded structure-of-arrays `float` copy of
/// the support set, vectorised for the processor it runs on (SSE2, AVX2 or AVX-512: simd.h);
/// `scoreExact` sums in `double` over the same points, the precision used in training.
class Model {
 public:
  /// `supportConfigurations`: one support configuration per row (joint values); `weights`: one
  /// per row. The support features are computed with `features`. Throws InvalidArgument on
  /// mismatched sizes, non-finite values or dimension 0 or above kMaxDimension.
  Model(FeatureMap features, Kernel kernel, Configurations supportConfigurations,
        Eigen::VectorXd weights);

  /// Joint values per configuration (what queries take).
  std::size_t dim() const { return features_.configurationDim(); }
  /// Features per configuration (what the kernel compares).
  std::size_t featureDim() const { return features_.featureDim(); }
  std::size_t supportCount() const { return static_cast<std::size_t>(weights_.size()); }
  const FeatureMap& features() const { return features_; }
  const JointLimits& limits() const { return features_.limits(); }
  const Kernel& kernel() const { return kernel_; }
  /// Support configurations (joint values), one per row.
  const Configurations& supportConfigurations() const { return configurations_; }
  /// Their features, one per row.
  const Eigen::MatrixXd& supportFeatures() const { return support_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  /// A checksum of the support set and weights (and of the float copies queries read), taken
  /// when the model was built: a model never changes, so computeChecksum() always equals it.
  std::uint64_t checksum() const { return checksum_; }
  std::uint64_t computeChecksum() const;

  /// f(q) on the vectorised float path. q: dim() joint values. Throws InvalidArgument on a
  /// non-finite value.
  double score(const double* q) const;
  double score(std::span<const double> q) const;
  /// True when f(q) > 0, i.e. the model predicts a collision (label +1). A model with a point
  /// field (withPointField) reads f from its grids where they decide the sign and sums every term
  /// where they do not: the same answer as score(q) > 0 (or, with FieldAnswers::Estimate, the
  /// sign of the grids' estimate, which differs from it only on the model's boundary).
  bool inCollision(const double* q) const;
  bool inCollision(std::span<const double> q) const;

  /// f(q) summed in double precision (the reference for the float path).
  double scoreExact(const double* q) const;

  /// Index of the first of n configurations (row by row in `q`, n * dim() values) that the model
  /// predicts in collision, or n when it predicts all free (with a point field: as inCollision,
  /// row by row). Computes the features of sixteen
  /// configurations at once, scores four per pass over the support set and stops after the pass
  /// with the first hit, so callers order the rows
  /// to find collisions early (e.g. bisection order along a motion).
  std::size_t firstInCollision(const double* q, std::size_t n) const;
  /// The same for every row of q; throws InvalidArgument when q does not have dim() columns.
  std::size_t firstInCollision(const Configurations& q) const;

  /// f for n configurations stored row by row in `q` (n * dim() values), written to `out`; four
  /// per pass over the support set, each support block loaded once for all four.
  void scoreBatch(const double* q, std::size_t n, double* out) const;
  /// Scores of every row of `q`.
  Eigen::VectorXd scoreBatch(const Configurations& q) const;

  /// f(q) and its gradient with respect to the joint values: the kernel's derivative in feature
  /// space (every term: the whole vector's and each point's), through the features' Jacobian
  /// (joint scaling's scales, or the control points' Jacobian from forward kinematics, in double).
  /// Analytic; the kernel terms summed in float over the query copies the scores read, in one
  /// pass on the SIMD path in use (as `score`). Throws InvalidArgument on a wrong size or a
  /// non-finite value.
  struct ScoreGradient {
    double score = 0;
    Eigen::VectorXd gradient;  ///< dim() values
  };
  ScoreGradient scoreGradient(std::span<const double> q) const;
  /// The same summed in double over the double support set (the reference, as scoreExact).
  ScoreGradient scoreGradientExact(std::span<const double> q) const;
  /// The same for every row of q: scores (n) and gradients (n x dim(), row by row).
  struct ScoreGradients {
    Eigen::VectorXd scores;
    Configurations gradients;
  };
  ScoreGradients scoreGradients(const Configurations& q) const;

  /// Whether withPointField can tabulate this model: point terms of 3 features (Kernel::block 3,
  /// the positions of control points) and no whole-vector term (wholeShare 0).
  bool hasOnlyPointTerms() const;
  /// A copy of this model whose collision answers (inCollision, firstInCollision) read its point
  /// terms from grids where they decide the sign (point_field.h; options.answers says how the
  /// rest are answered: exactly by default, or by the grids' estimate); score, scoreBatch and the
  /// gradients still sum every term. Costs (grid nodes x |S|) kernel terms, shared with the
  /// process's helper thread. Throws InvalidArgument on bad options, on a grid larger than
  /// options.maxNodes, and unless hasOnlyPointTerms(), naming what the kernel has instead.
  std::shared_ptr<const Model> withPointField(const PointFieldOptions& options = {}) const;
  /// The grids of withPointField, or null.
  const PointField* pointField() const { return pointField_.get(); }

 private:
  friend class Trainer;
  /// For the trainer, which holds the support features already (computed from the same
  /// configurations with the same map): no second forward kinematics per update.
  Model(FeatureMap features, Kernel kernel, Configurations supportConfigurations,
        Eigen::MatrixXd supportFeatures, Eigen::VectorXd weights);
  /// Throws InvalidArgument on a bad kernel, dimension, size or weight.
  void validateSupport() const;
  /// The float structure-of-arrays copies the queries read; throws InvalidArgument on a weight or
  /// support feature beyond float range.
  void buildQueryCopies();

  /// f(q) on the float path, and df/dq into `gradient` (dim() values); `jacobian` is scratch of
  /// featureDim() * dim() values. q is not checked.
  double scoreGradientInto(const double* q, double* jacobian, double* gradient) const;
  /// The float copies, as the kernel sums of simd.h read them.
  detail::SupportView supportView() const;
  float scoreInputFloat(const float* x) const;
  /// The support set as one point term g sees it: 3 features from 3g, one term (point_field.cpp).
  detail::SupportView termView(std::size_t g) const;
  /// f(x) > 0 answered from the point field, refining its least certain terms (point_field.cpp).
  bool inCollisionByField(const float* x) const;
  /// f of the first `count` (1 to 4) of four consecutive feature rows of xs (a short group
  /// padded by the caller), in one pass over the support set.
  void scoreGroup(const float* xs, std::size_t count, float* out) const;
  /// Scores the n configurations of q in groups of up to four (features sixteen at a time),
  /// calling visit(first row, count, scores) for each group until it returns true.
  template <class Visit>
  void scoreInGroups(const double* q, std::size_t n, Visit visit) const;
  /// Float features of n configurations (q and x row by row, n at most 16); throws
  /// InvalidArgument on a non-finite joint value, naming its row as firstRow + its index.
  void toFeatures(const double* q, std::size_t n, float* x, std::size_t firstRow) const;

  FeatureMap features_;
  Kernel kernel_;
  Configurations configurations_;
  Eigen::MatrixXd support_;  // features of configurations_
  Eigen::VectorXd weights_;

  // Hot-path copies: support_ transposed to structure-of-arrays float, each dimension padded to
  // a multiple of the SIMD block with zero-weight points. Aligned to 64 bytes so that no block
  // load straddles two cache lines (10% of a standalone kernel sum at d = 12).
  using AlignedFloats = std::vector<float, detail::CacheLineAllocator<float>>;
  std::size_t paddedCount_ = 0;
  AlignedFloats supportSoa_;  // dim() blocks of paddedCount_ values
  AlignedFloats weightsF_;    // paddedCount_ values
  std::uint64_t checksum_ = 0;
  std::shared_ptr<const PointField> pointField_;  // null unless withPointField made this copy
};

/// The fewest support points at which withFastestAnswers gives a model its point field. At |S|
/// 234 the field answered 1.4x faster than the full sum (446 against 632 ns, built in 59 ms; at
/// 724, 4.1x); smaller models were not measured, and their sum is a few hundred nanoseconds that
/// the build would have to win back (docs/performance.md, "Answers from tabulated point terms").
inline constexpr std::size_t kPointFieldMinSupport = 200;

/// `model` with its point field answering by its estimate alone (Model::withPointField, default
/// spacing, FieldAnswers::Estimate) when it has point terms only and at least
/// kPointFieldMinSupport support points, else `model` itself: the fastest way this library has to
/// give its answers to a few plans (`fastron plan --model`), whose paths are verified anyway. The
/// estimate differs from the full sum's sign only on the model's boundary (on the scene models
/// measured, 9-32 of 20000 answers, accuracy and TPR against FCL unchanged).
std::shared_ptr<const Model> withFastestAnswers(std::shared_ptr<const Model> model);

/// A joint-space model from support points given in input space [-1, 1]^d, where the paper's SVM
/// baselines train.
std::shared_ptr<const Model> jointSpaceModel(const JointLimits& limits, Kernel kernel,
                                             const Eigen::MatrixXd& inputPoints,
                                             Eigen::VectorXd weights);

}  // namespace fastron
