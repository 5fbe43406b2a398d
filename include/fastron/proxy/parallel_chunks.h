#pragma once
// Work split into chunks handed out from a shared counter to a few threads: the one way Fastron
// spreads exact checks over the cores (labelling, path verification).

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace fastron {

/// Calls body(begin, end) for the chunks [0, chunk), [chunk, 2 chunk), ... of [0, n), in that
/// order of hand-out, on `threads` threads: the calling thread and threads - 1 started for the
/// call (0: every hardware thread; never more than there are chunks). The first exception a body
/// throws stops the hand-out and is rethrown here once every thread has finished.
template <class Body>
void forEachChunk(std::size_t n, std::size_t chunk, unsigned threads, const Body& body) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, (n + chunk - 1) / chunk));
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto work = [&] {
    try {
      for (std::size_t begin = next.fetch_add(chunk); begin < n; begin = next.fetch_add(chunk)) {
        body(begin, std::min(n, begin + chunk));
      }
    } catch (...) {
      const std::lock_guard lock(errorMutex);
      if (!error) error = std::current_exception();
      next.store(n);  // stop the other threads early
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
}

}  // namespace fastron
