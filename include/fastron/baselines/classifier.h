#pragma once
// One interface for every C-space classifier the paper compares (Fastron, ISVM, SSVM, LIBSVM).

#include <memory>
#include <span>
#include <string>

#include "fastron/core/export.h"
#include "fastron/core/model.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

/// A binary classifier of configurations (joint values): a positive score predicts a collision.
class Classifier {
 public:
  virtual ~Classifier() = default;
  virtual std::string name() const = 0;
  /// Trains on labelled configurations (+1 in collision, -1 free), replacing any earlier model.
  virtual void train(const Configurations& q, std::span<const std::int8_t> labels) = 0;
  virtual double score(const double* q) const = 0;
  bool predict(const double* q) const { return score(q) > 0; }
  virtual std::size_t supportCount() const = 0;
};

/// f(q) = bias + sum_i w_i k(s_i, q): what every kernel method here learns. Evaluated with the
/// same vectorised engine as Fastron's model, so query times compare the models, not the code.
struct KernelExpansion {
  std::shared_ptr<const Model> terms;  ///< support points and weights
  double bias = 0;

  double score(const double* q) const { return terms->score(q) + bias; }
  std::size_t supportCount() const { return terms ? terms->supportCount() : 0; }
};

}  // namespace fastron
