#include "fastron/proxy/labelling.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

namespace fastron {

Labels labelConfigurations(const CollisionChecker& checker, const Configurations& q,
                           unsigned threads) {
  const auto n = static_cast<std::size_t>(q.rows());
  const auto d = static_cast<std::size_t>(q.cols());
  Labels labels(n);
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  constexpr std::size_t kChunk = 16;  // rows handed out at a time: balances uneven check costs
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, (n + kChunk - 1) / kChunk));

  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto work = [&] {
    try {
      for (std::size_t begin = next.fetch_add(kChunk); begin < n; begin = next.fetch_add(kChunk)) {
        const std::size_t end = std::min(n, begin + kChunk);
        for (std::size_t i = begin; i < end; ++i) {
          const bool hit = checker.inCollision({q.data() + i * d, d});
          labels[i] = hit ? std::int8_t{1} : std::int8_t{-1};
        }
      }
    } catch (...) {
      const std::lock_guard lock(errorMutex);
      if (!error) error = std::current_exception();
      next.store(n);  // stop the other workers early
    }
  };
  if (threads <= 1) {
    work();
  } else {
    std::vector<std::jthread> pool;
    pool.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
  }  // the pool joins here
  if (error) std::rethrow_exception(error);
  return labels;
}

}  // namespace fastron
