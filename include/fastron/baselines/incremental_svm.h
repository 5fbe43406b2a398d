#pragma once
// Incremental SVM: exact incremental learning of a soft-margin kernel SVM with a bias, after
// Cauwenberghs and Poggio (NIPS 2000), as in Diehl and Cauwenberghs' implementation the paper
// used. Each new point is added by growing its weight while every other point keeps its KKT
// conditions, moving points between the margin, error and reserve sets as they are crossed.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "fastron/baselines/classifier.h"
#include "fastron/core/export.h"
#include "fastron/core/joint_limits.h"
#include "fastron/core/kernel.h"

namespace FASTRON_API fastron {

class IncrementalSvm {
 public:
  IncrementalSvm(Kernel kernel, double C);

  /// Learns one point (input space) exactly: afterwards every point satisfies the KKT
  /// conditions of the SVM trained on all points so far.
  void add(std::span<const double> x, std::int8_t label);

  /// f(x) = sum_i alpha_i y_i k(x_i, x) + b, x in input space.
  double decision(const double* x) const;

  std::size_t size() const { return y_.size(); }
  const Eigen::VectorXd& point(std::size_t i) const { return x_[i]; }  ///< input space
  double label(std::size_t i) const { return y_[i]; }
  /// Points with alpha > 0 (margin and error vectors).
  std::size_t supportCount() const;
  double bias() const { return b_; }
  const std::vector<double>& alphas() const { return alpha_; }
  /// Largest violation of the KKT conditions over all points (0 when exact).
  double maxKktViolation() const;
  /// The learned function as a kernel expansion over the support vectors.
  KernelExpansion expansion(const JointLimits& limits) const;

 private:
  enum class Set : std::uint8_t { Margin, Error, Reserve };
  double k(std::size_t i, std::size_t j) const;
  double q(std::size_t i, std::size_t j) const { return y_[i] * y_[j] * k(i, j); }
  void rebuildR();
  void joinMargin(std::size_t i);
  void leaveMargin(std::size_t position);
  void learn(std::size_t c);

  Kernel kernel_;
  double C_;
  std::vector<Eigen::VectorXd> x_;
  std::vector<double> y_, alpha_, g_;  // g_i = y_i f(x_i) - 1
  std::vector<Set> set_;
  std::vector<std::size_t> margin_;  // margin vectors, in the order of R's rows 1..
  Eigen::MatrixXd R_;                // inverse of [0 y_S^T; y_S Q_SS]
  double b_ = 0;
};

/// Pan et al.'s active learning around an incremental SVM, as the paper's Algorithm 3 states.
struct IsvmActiveLearningParams {
  double C = 10;
  std::size_t initialPoints = 200;  ///< X_init, uniform
  std::size_t maxAdded = 1800;      ///< A_max: points added after X_init
  std::size_t batch = 100;          ///< N_A: collision checks per active-learning update
  double exploreProbability = 0.5;  ///< P_explore at the start
  double exploreStep = 0.05;        ///< Delta P_explore
  double errorThreshold = 0.1;      ///< err_thres
  std::uint64_t seed = 1;
};

/// Labels configurations given in joint space (the oracle).
using Labeler = std::function<Labels(const Configurations&)>;

/// ISVM as a Classifier: train() learns the given points one by one; trainActively() runs
/// Algorithm 3 against an oracle.
class IsvmClassifier final : public Classifier {
 public:
  IsvmClassifier(JointLimits limits, Kernel kernel, IsvmActiveLearningParams params);
  std::string name() const override { return "ISVM"; }
  void train(const Configurations& q, std::span<const std::int8_t> labels) override;
  /// Algorithm 3: returns the number of configurations labelled.
  std::size_t trainActively(const Labeler& oracle);
  double score(const double* q) const override { return model_.score(q); }
  std::size_t supportCount() const override { return model_.supportCount(); }
  const IncrementalSvm& svm() const { return svm_; }

 private:
  JointLimits limits_;
  Kernel kernel_;
  IsvmActiveLearningParams params_;
  IncrementalSvm svm_;
  KernelExpansion model_;
};

}  // namespace fastron
