#pragma once
// Analytic collision worlds for tests: exact labels without any geometry library.

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "fastron/core/model.h"
#include "fastron/core/trainer.h"
#include "fastron/core/types.h"

namespace fastron::test {

/// Balls of one radius in [-1, 1]^d; a configuration collides when it lies inside any ball.
struct BallWorld {
  std::vector<Eigen::VectorXd> centers;
  double radius = 0.3;

  static BallWorld random(std::size_t dim, std::size_t balls, double radius, std::uint64_t seed) {
    Rng rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    BallWorld world;
    world.radius = radius;
    for (std::size_t b = 0; b < balls; ++b) {
      Eigen::VectorXd c(static_cast<Eigen::Index>(dim));
      for (auto& v : c) v = u(rng);
      world.centers.push_back(c);
    }
    return world;
  }

  bool inCollision(const double* q) const {
    for (const auto& c : centers) {
      const Eigen::Map<const Eigen::VectorXd> x(q, c.size());
      if ((x - c).squaredNorm() < radius * radius) return true;
    }
    return false;
  }

  /// Shifts every ball by `step` along each axis (an obstacle motion).
  void move(double step) {
    for (auto& c : centers) c.array() += step;
  }

  Labels label(const Configurations& q) const {
    Labels y(static_cast<std::size_t>(q.rows()));
    for (Eigen::Index i = 0; i < q.rows(); ++i)
      y[static_cast<std::size_t>(i)] = inCollision(q.row(i).data()) ? 1 : -1;
    return y;
  }
};

/// n uniform points in [-1, 1]^d.
inline Configurations uniformPoints(std::size_t n, std::size_t dim, std::uint64_t seed) {
  Rng rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Configurations q(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(dim));
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    for (Eigen::Index j = 0; j < q.cols(); ++j) q(i, j) = u(rng);
  }
  return q;
}

/// Labels drawn at random: the hardest data for Claim 1 (nothing but distinct points).
inline Labels randomLabels(std::size_t n, std::uint64_t seed) {
  Rng rng(seed);
  std::bernoulli_distribution coin(0.5);
  Labels y(n);
  for (auto& v : y) v = coin(rng) ? 1 : -1;
  return y;
}

/// A model of `kernel` and `beta` trained to convergence on n uniform points of [-1, 1]^d (seed)
/// labelled by a random world of 5 balls (seed + 1) up to `maxBallDim` dimensions, where balls
/// fill a good share of the space, and by random labels above it, where they would fill almost
/// nothing.
inline std::shared_ptr<const Model> trainedOnBalls(std::size_t dim, std::size_t n, Kernel kernel,
                                                   double beta, std::uint64_t seed,
                                                   std::size_t maxBallDim) {
  const Configurations q = uniformPoints(n, dim, seed);
  TrainParams p;
  p.kernel = kernel;
  p.beta = beta;
  p.maxIterations = 1'000'000;
  p.maxSupportPoints = n;
  Trainer trainer(JointLimits::unitBox(dim), p);
  const double radius = 0.45 * std::sqrt(static_cast<double>(dim) / 2.0);
  trainer.addPoints(q, dim <= maxBallDim ? BallWorld::random(dim, 5, radius, seed + 1).label(q)
                                         : randomLabels(n, seed + 1));
  trainer.update();
  return trainer.model();
}

}  // namespace fastron::test
