#include "fastron/core/model.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>

#include "fastron/core/error.h"
#include "kernel_sums.h"

namespace fastron {
namespace {

constexpr std::size_t kLanes = detail::kSupportLanes;
constexpr std::size_t kQueries = detail::kQueriesPerPass;
// Configurations whose features are computed together (one per lane of the batched kinematics).
constexpr std::size_t kFeatureBatch = 16;

}  // namespace

Model::Model(FeatureMap features, Kernel kernel, Configurations supportConfigurations,
             Eigen::VectorXd weights)
    : features_(std::move(features)),
      kernel_(kernel),
      configurations_(std::move(supportConfigurations)),
      weights_(std::move(weights)) {
  validateSupport();
  // Checks that the configurations are finite. Rounded to float as a Trainer stores them, so a
  // model rebuilt from its configurations (a file) scores as the trained one did.
  support_ = features_.map(configurations_).cast<float>().cast<double>();
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
  validate(kernel_, featureDim());
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
  if (weights_.size() > 0 && weights_.cwiseAbs().maxCoeff() > kMaxFloatValue)
    throw InvalidArgument("weights must be at most 1e30 in magnitude (queries sum in float)");
  if (support_.size() > 0 && !(support_.cwiseAbs().maxCoeff() <= kMaxFloatValue)) {
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

detail::SupportView Model::supportView() const {
  return {supportSoa_.data(),
          weightsF_.data(),
          paddedCount_,
          featureDim(),
          static_cast<float>(kernel_.gamma),
          kernel_.type,
          kernel_.block,
          static_cast<float>(kernel_.wholeWeight()),
          static_cast<float>(kernel_.pointWeight(featureDim()))};
}

float Model::scoreInputFloat(const float* x) const {
  return detail::activeKernelSums().one(supportView(), x);
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

bool Model::inCollision(const double* q) const {
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): toFeatures fills it
  std::array<float, kMaxFeatureDimension> x;
  toFeatures(q, 1, x.data(), 0);
  return pointField_ ? inCollisionByField(x.data()) : scoreInputFloat(x.data()) > 0;
}

bool Model::inCollision(std::span<const double> q) const {
  checkConfiguration(q, dim());
  return inCollision(q.data());
}

double Model::scoreExact(const double* q) const {
  checkConfiguration(std::span<const double>(q, dim()), dim());
  Eigen::VectorXd x(support_.cols());
  features_.map(q, x.data());
  double f = 0;
  for (Eigen::Index i = 0; i < support_.rows(); ++i) {
    const auto s = [&](std::size_t c) { return support_(i, static_cast<Eigen::Index>(c)); };
    const auto xc = [&](std::size_t c) { return x[static_cast<Eigen::Index>(c)]; };
    f += weights_[i] * kernel_.between<double>(s, xc, featureDim());
  }
  return f;
}

void Model::scoreGroup(const float* xs, std::size_t count, float* out) const {
  if (count == 1) {  // a group of four costs 1.6 single queries: not worth it for one
    out[0] = scoreInputFloat(xs);
    return;
  }
  std::array<float, kQueries> scores;
  detail::activeKernelSums().four(supportView(), xs, scores.data());
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
  if (pointField_) {
    // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): toFeatures fills what is read
    std::array<float, kFeatureBatch * kMaxFeatureDimension> xs;
    const std::size_t d = featureDim();
    for (std::size_t i = 0; i < n; i += kFeatureBatch) {
      const std::size_t batch = std::min(kFeatureBatch, n - i);
      toFeatures(q + i * dim(), batch, xs.data(), i);
      for (std::size_t k = 0; k < batch; ++k) {
        if (inCollisionByField(xs.data() + k * d)) return i + k;
      }
    }
    return n;
  }
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
