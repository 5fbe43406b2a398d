#include "fastron/baselines/original_fastron_query.h"

#include <array>
#include <string>
#include <utility>

#include "fastron/core/error.h"

namespace fastron {

OriginalFastronQuery::OriginalFastronQuery(const Model& model)
    : features_(model.features()),
      support_(model.supportFeatures()),
      alpha_(model.weights().array()),
      twoOverGamma_(2.0 / model.kernel().gamma) {
  if (!accepts(model.kernel())) {
    throw InvalidArgument(
        "the original Fastron's query sums the rational-quadratic kernel over the whole "
        "feature vector; this model's kernel is " +
        std::string(toString(model.kernel().type)) + ", " +
        describeTerms(model.kernel(), model.featureDim()));
  }
}

namespace {

/// t = c + (s_0 - x_0)^2 + ... + (s_{d-1} - x_{d-1})^2 as one expression: the original's
/// unrolled cases (4 to 7 features), one pass over the support set.
template <std::size_t... J>
void unrolledDistances(const Eigen::MatrixXd& s, const double* x, double c, Eigen::ArrayXd& t,
                       std::index_sequence<J...> /*columns*/) {
  t = (c + ... + (s.col(J).array() - x[J]).square());
}

}  // namespace

double OriginalFastronQuery::scoreFeatures(const double* x) const {
  // As the original's member array: allocated once, not per query.
  thread_local Eigen::ArrayXd t;
  t.resize(support_.rows());
  switch (support_.cols()) {
    case 4:
      unrolledDistances(support_, x, twoOverGamma_, t, std::make_index_sequence<4>{});
      break;
    case 5:
      unrolledDistances(support_, x, twoOverGamma_, t, std::make_index_sequence<5>{});
      break;
    case 6:
      unrolledDistances(support_, x, twoOverGamma_, t, std::make_index_sequence<6>{});
      break;
    case 7:
      unrolledDistances(support_, x, twoOverGamma_, t, std::make_index_sequence<7>{});
      break;
    default:
      t = twoOverGamma_ + (support_.col(0).array() - x[0]).square();
      for (Eigen::Index j = 1; j < support_.cols(); ++j) {
        t += (support_.col(j).array() - x[j]).square();
      }
  }
  return (alpha_ / (t * t)).sum();
}

bool OriginalFastronQuery::inCollision(const double* q) const {
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-member-init): map fills what is read
  std::array<double, kMaxFeatureDimension> x;
  features_.map(q, x.data());
  return scoreFeatures(x.data()) > 0;
}

}  // namespace fastron
