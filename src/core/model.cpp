#include "fastron/core/model.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <type_traits>

#include "fastron/core/error.h"

namespace fastron {
namespace {

// The float kernel sum runs over fixed-size blocks of support points; Eigen maps each block onto
// SIMD registers (one AVX-512 or two AVX2 registers) and vectorises exp() for the Gaussian.
constexpr std::size_t kLanes = 16;
using Lanes = Eigen::Array<float, kLanes, 1>;

template <KernelType type>
Lanes kernelOf(const Lanes& r2, float gamma) {
  return kernelOfSquaredDistance<type>(r2, gamma);
}

/// Calls f(std::integral_constant<std::size_t, D>) with D = dim for the feature dimensions of
/// planar tests, 6- and 7-joint arms and 3- and 4-point task spaces, D = 0 for any other. Known
/// at compile time, the loop over features unrolls into straight code: with the split sum below,
/// 1.2 to 1.7 times faster single queries at d = 7 and 12 (BM_QueryFloat, BM_TaskSpaceQuery).
template <class F>
decltype(auto) withDimension(std::size_t dim, F f) {
  switch (dim) {
    case 2:
      return f(std::integral_constant<std::size_t, 2>{});
    case 6:
      return f(std::integral_constant<std::size_t, 6>{});
    case 7:
      return f(std::integral_constant<std::size_t, 7>{});
    case 9:
      return f(std::integral_constant<std::size_t, 9>{});
    case 12:
      return f(std::integral_constant<std::size_t, 12>{});
    default:
      return f(std::integral_constant<std::size_t, 0>{});
  }
}

// From this many features on, r^2 is summed in two chains (even and odd features) instead of
// one: the chain of dependent multiply-adds per block is half as long, so more blocks are in
// flight at once (on top of the unrolling: task-space batches of 16 at |S| 300 1.1x faster,
// single queries from within noise to 1.2x). At d = 2 and 4 the split measured 0.7-0.9x.
constexpr std::size_t kPairedFrom = 6;

/// Calls f(kernel, paired) with the kernel type and whether r^2 is split in two chains, both as
/// compile-time constants. The one place that decides the split: the single and the batched sums
/// must compute r^2 alike, so that their scores are the same numbers
/// (Model.EveryDimensionScoresAlikeOnEveryPath).
template <class F>
decltype(auto) withSumShape(KernelType type, std::size_t dim, F f) {
  const auto withSplit = [&](auto kernel) {
    return dim >= kPairedFrom ? f(kernel, std::true_type{}) : f(kernel, std::false_type{});
  };
  using RationalQuadratic = std::integral_constant<KernelType, KernelType::RationalQuadratic>;
  using Gaussian = std::integral_constant<KernelType, KernelType::Gaussian>;
  return type == KernelType::RationalQuadratic ? withSplit(RationalQuadratic{})
                                               : withSplit(Gaussian{});
}

/// The kernel sum over the support set; `dim` is D when D is not 0.
template <KernelType type, std::size_t D, bool paired>
float kernelSum(const float* soa, const float* weights, std::size_t padded, std::size_t dim,
                const float* x, float gamma) {
  if constexpr (D != 0) dim = D;
  Lanes sum = Lanes::Zero();
  for (std::size_t b = 0; b < padded; b += kLanes) {
    Lanes r2 = Lanes::Zero(), odd = Lanes::Zero();
    std::size_t j = 0;
    for (; paired && j + 1 < dim; j += 2) {
      r2 += (Eigen::Map<const Lanes>(soa + j * padded + b) - x[j]).square();
      odd += (Eigen::Map<const Lanes>(soa + (j + 1) * padded + b) - x[j + 1]).square();
    }
    for (; j < dim; ++j) r2 += (Eigen::Map<const Lanes>(soa + j * padded + b) - x[j]).square();
    if constexpr (paired) r2 += odd;
    sum += Eigen::Map<const Lanes>(weights + b) * kernelOf<type>(r2, gamma);
  }
  return sum.sum();
}

// kQueries kernel sums in one pass over the support set: each block of support coordinates is
// loaded once for all of them (the batch and edge queries of motion planning).
constexpr std::size_t kQueries = 4;
// Configurations whose features are computed together (one per lane of the batched kinematics).
constexpr std::size_t kFeatureBatch = 16;

// (The dimension stays a run-time value here: unrolled over the features, four queries at a time
// measured 1.1-1.7 times slower.)
template <KernelType type, bool paired>
std::array<float, kQueries> kernelSums(const float* soa, const float* weights, std::size_t padded,
                                       std::size_t dim, const float* xs, float gamma) {
  std::array<Lanes, kQueries> sums;
  for (Lanes& s : sums) s.setZero();
  for (std::size_t b = 0; b < padded; b += kLanes) {
    std::array<Lanes, kQueries> r2, odd;
    for (Lanes& r : r2) r.setZero();
    for (Lanes& r : odd) r.setZero();
    std::size_t j = 0;
    for (; paired && j + 1 < dim; j += 2) {
      const Lanes c0 = Eigen::Map<const Lanes>(soa + j * padded + b);
      const Lanes c1 = Eigen::Map<const Lanes>(soa + (j + 1) * padded + b);
      for (std::size_t q = 0; q < kQueries; ++q) {
        r2[q] += (c0 - xs[q * dim + j]).square();
        odd[q] += (c1 - xs[q * dim + j + 1]).square();
      }
    }
    for (; j < dim; ++j) {
      const Lanes c = Eigen::Map<const Lanes>(soa + j * padded + b);
      for (std::size_t q = 0; q < kQueries; ++q) r2[q] += (c - xs[q * dim + j]).square();
    }
    const Lanes w = Eigen::Map<const Lanes>(weights + b);
    for (std::size_t q = 0; q < kQueries; ++q) {
      if constexpr (paired) r2[q] += odd[q];
      sums[q] += w * kernelOf<type>(r2[q], gamma);
    }
  }
  std::array<float, kQueries> out;
  for (std::size_t q = 0; q < kQueries; ++q) out[q] = sums[q].sum();
  return out;
}

}  // namespace

Model::Model(FeatureMap features, Kernel kernel, Configurations supportConfigurations,
             Eigen::VectorXd weights)
    : features_(std::move(features)),
      kernel_(kernel),
      configurations_(std::move(supportConfigurations)),
      weights_(std::move(weights)) {
  validateSupport();
  support_ = features_.map(configurations_);  // checks that the configurations are finite
  buildQueryCopies();
  checksum_ = computeChecksum();
}

Model::Model(FeatureMap features, Kernel kernel, Configurations supportConfigurations,
             Eigen::MatrixXd supportFeatures, Eigen::VectorXd weights)
    : features_(std::move(features)),
      kernel_(kernel),
      configurations_(std::move(supportConfigurations)),
      support_(std::move(supportFeatures)),
      weights_(std::move(weights)) {
  validateSupport();
  buildQueryCopies();
  checksum_ = computeChecksum();
}

std::uint64_t Model::computeChecksum() const {
  // FNV-1a over 8-byte words: a few microseconds for a support set of hundreds.
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  const auto mix = [&](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; i += 8) {
      std::uint64_t word = 0;
      std::memcpy(&word, p + i, std::min<std::size_t>(8, bytes - i));
      hash = (hash ^ word) * 0x100000001b3ULL;
    }
  };
  mix(configurations_.data(), sizeof(double) * static_cast<std::size_t>(configurations_.size()));
  mix(weights_.data(), sizeof(double) * static_cast<std::size_t>(weights_.size()));
  mix(supportSoa_.data(), sizeof(float) * supportSoa_.size());
  mix(weightsF_.data(), sizeof(float) * weightsF_.size());
  return hash;
}

void Model::validateSupport() const {
  validate(kernel_);
  const std::size_t d = dim();
  if (d == 0 || d > kMaxDimension) {
    throw InvalidArgument("model dimension must be between 1 and " + std::to_string(kMaxDimension) +
                          ", got " + std::to_string(d));
  }
  if (static_cast<std::size_t>(configurations_.cols()) != d) {
    throw InvalidArgument("support configurations have " + std::to_string(configurations_.cols()) +
                          " columns but the joint limits have dimension " + std::to_string(d));
  }
  if (configurations_.rows() != weights_.size()) {
    throw InvalidArgument(std::to_string(configurations_.rows()) + " support points but " +
                          std::to_string(weights_.size()) + " weights");
  }
  if (!weights_.allFinite()) throw InvalidArgument("weights must be finite");
}

void Model::buildQueryCopies() {
  // The copies are float: a weight or feature beyond its range would be infinite there (and
  // 0 * inf = NaN in the kernel sum). The margin leaves room for sums of many of them.
  constexpr double kMaxQueryValue = 1e30;
  if (weights_.size() > 0 && weights_.cwiseAbs().maxCoeff() > kMaxQueryValue)
    throw InvalidArgument("weights must be at most 1e30 in magnitude (queries sum in float)");
  if (support_.size() > 0 && !(support_.cwiseAbs().maxCoeff() <= kMaxQueryValue)) {
    throw InvalidArgument(
        "support features must be at most 1e30 in magnitude (a support configuration far outside "
        "the joint limits?)");
  }
  const std::size_t featureCount = featureDim();
  const std::size_t n = supportCount();
  paddedCount_ = (n + kLanes - 1) / kLanes * kLanes;
  supportSoa_.assign(featureCount * paddedCount_, 0.0f);
  weightsF_.assign(paddedCount_, 0.0f);  // padding points have weight 0: they add nothing
  for (std::size_t i = 0; i < n; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    for (std::size_t j = 0; j < featureCount; ++j) {
      supportSoa_[j * paddedCount_ + i] =
          static_cast<float>(support_(row, static_cast<Eigen::Index>(j)));
    }
    weightsF_[i] = static_cast<float>(weights_[row]);
  }
}

void Model::toFeatures(const double* q, std::size_t n, float* x, std::size_t firstRow) const {
  for (std::size_t j = 0; j < n * dim(); ++j) {
    if (!std::isfinite(q[j])) {
      throw InvalidArgument(
          "configuration value [" + std::to_string(j % dim()) + "] is not finite (" +
          std::to_string(q[j]) + ")" +
          (n > 1 ? " in configuration " + std::to_string(firstRow + j / dim()) : ""));
    }
  }
  features_.mapBatch(q, n, x);
}

float Model::scoreInputFloat(const float* x) const {
  const auto gamma = static_cast<float>(kernel_.gamma);
  return withDimension(featureDim(), [&](auto d) {
    return withSumShape(kernel_.type, featureDim(), [&](auto kernel, auto paired) {
      return kernelSum<decltype(kernel)::value, decltype(d)::value, decltype(paired)::value>(
          supportSoa_.data(), weightsF_.data(), paddedCount_, featureDim(), x, gamma);
    });
  });
}

double Model::score(const double* q) const {
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): toFeatures fills it
  std::array<float, kMaxFeatureDimension> x;
  toFeatures(q, 1, x.data(), 0);
  return scoreInputFloat(x.data());
}

double Model::score(std::span<const double> q) const {
  checkConfiguration(q, dim());
  return score(q.data());
}

double Model::scoreExact(const double* q) const {
  checkConfiguration(std::span<const double>(q, dim()), dim());
  Eigen::VectorXd x(support_.cols());
  features_.map(q, x.data());
  double f = 0;
  for (Eigen::Index i = 0; i < support_.rows(); ++i) {
    f += weights_[i] * kernel_((support_.row(i).transpose() - x).squaredNorm());
  }
  return f;
}

void Model::scoreGroup(const float* xs, std::size_t count, float* out) const {
  if (count == 1) {  // a group of four costs 1.6 single queries: not worth it for one
    out[0] = scoreInputFloat(xs);
    return;
  }
  const auto gamma = static_cast<float>(kernel_.gamma);
  const auto scores = withSumShape(kernel_.type, featureDim(), [&](auto kernel, auto paired) {
    return kernelSums<decltype(kernel)::value, decltype(paired)::value>(
        supportSoa_.data(), weightsF_.data(), paddedCount_, featureDim(), xs, gamma);
  });
  std::copy_n(scores.begin(), count, out);
}

template <class Visit>
void Model::scoreInGroups(const double* q, std::size_t n, Visit visit) const {
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): toFeatures fills what is read
  std::array<float, kFeatureBatch * kMaxFeatureDimension> xs;
  std::array<float, kQueries> f{};
  const std::size_t d = featureDim();
  for (std::size_t i = 0; i < n; i += kFeatureBatch) {
    const std::size_t batch = std::min(kFeatureBatch, n - i);
    toFeatures(q + i * dim(), batch, xs.data(), i);
    // A short last group repeats its last row (the lanes are computed anyway); the buffer holds
    // whole groups, so the copies stay inside it.
    for (std::size_t k = batch; k % kQueries != 0; ++k) {
      std::copy_n(xs.data() + (batch - 1) * d, d, xs.data() + k * d);
    }
    for (std::size_t g = 0; g < batch; g += kQueries) {
      const std::size_t count = std::min(kQueries, batch - g);
      scoreGroup(xs.data() + g * d, count, f.data());
      if (visit(i + g, count, f.data())) return;
    }
  }
}

std::size_t Model::firstInCollision(const double* q, std::size_t n) const {
  std::size_t hit = n;
  scoreInGroups(q, n, [&](std::size_t first, std::size_t count, const float* f) {
    for (std::size_t k = 0; k < count; ++k) {
      if (f[k] > 0) {
        hit = first + k;
        return true;
      }
    }
    return false;
  });
  return hit;
}

void Model::scoreBatch(const double* q, std::size_t n, double* out) const {
  scoreInGroups(q, n, [&](std::size_t first, std::size_t count, const float* f) {
    std::copy_n(f, count, out + first);
    return false;
  });
}

namespace {

void checkColumns(const Configurations& q, std::size_t dim) {
  if (static_cast<std::size_t>(q.cols()) != dim) {
    throw InvalidArgument("configurations have " + std::to_string(q.cols()) +
                          " columns, the model has dimension " + std::to_string(dim));
  }
}

}  // namespace

Eigen::VectorXd Model::scoreBatch(const Configurations& q) const {
  checkColumns(q, dim());
  Eigen::VectorXd out(q.rows());
  scoreBatch(q.data(), static_cast<std::size_t>(q.rows()), out.data());
  return out;
}

std::size_t Model::firstInCollision(const Configurations& q) const {
  checkColumns(q, dim());
  return firstInCollision(q.data(), static_cast<std::size_t>(q.rows()));
}

std::shared_ptr<const Model> jointSpaceModel(const JointLimits& limits, Kernel kernel,
                                             const Eigen::MatrixXd& inputPoints,
                                             Eigen::VectorXd weights) {
  return std::make_shared<const Model>(FeatureMap::jointScaling(limits), kernel,
                                       limits.toJoint(Configurations(inputPoints)),
                                       std::move(weights));
}

}  // namespace fastron
