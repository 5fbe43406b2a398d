#include "fastron/proxy/labelling.h"

#include "fastron/proxy/parallel_chunks.h"

namespace fastron {

Labels labelConfigurations(const CollisionChecker& checker, const Configurations& q,
                           unsigned threads) {
  const auto n = static_cast<std::size_t>(q.rows());
  const auto d = static_cast<std::size_t>(q.cols());
  Labels labels(n);
  constexpr std::size_t kChunk = 16;  // rows handed out at a time: balances uneven check costs
  forEachChunk(n, kChunk, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      labels[i] = checker.inCollision({q.data() + i * d, d}) ? std::int8_t{1} : std::int8_t{-1};
    }
  });
  return labels;
}

}  // namespace fastron
