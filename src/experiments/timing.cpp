#include "fastron/experiments/timing.h"

#include <chrono>
#include "fastron/core/parallel_chunks.h"

namespace fastron::experiments {

double meanSecondsPerCall(const Configurations& q, const std::function<bool(const double*)>& fn,
                          double minSeconds) {
  using Clock = std::chrono::steady_clock;
  std::size_t calls = 0;
  [[maybe_unused]] volatile bool sink = false;  // keeps the calls from being optimised away
  const auto start = Clock::now();
  do {
    for (Eigen::Index i = 0; i < q.rows(); ++i) sink = fn(q.row(i).data());
    calls += static_cast<std::size_t>(q.rows());
  } while (std::chrono::duration<double>(Clock::now() - start).count() < minSeconds &&
           q.rows() > 0);
  return calls == 0 ? std::nan("")
                    : std::chrono::duration<double>(Clock::now() - start).count() /
                          static_cast<double>(calls);
}

double meanSecondsPerCheck(const Configurations& q, const CollisionChecker& checker,
                           double minSeconds) {
  const auto d = static_cast<std::size_t>(q.cols());
  return meanSecondsPerCall(
      q,
      [&](const double* x) {
        return checker.inCollision({x, d});
      },
      minSeconds);
}

std::vector<double> clearances(const SceneChecker& exact, const Configurations& q) {
  std::vector<double> distance(static_cast<std::size_t>(q.rows()));
  forEachChunk(distance.size(), 8, 0, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      distance[i] = exact.distance({q.row(static_cast<Eigen::Index>(i)).data(), exact.dof()});
    }
  });
  return distance;
}

}  // namespace fastron::experiments
