#pragma once
// Work split into chunks handed out from a shared counter to a few threads: the one way Fastron
// spreads exact work over the cores (labelling, path verification, self-pair tables). The helper
// threads are long-lived workers that sleep between calls: waking one took about 12 us on the
// project's 2-core machine, starting one 30 to 300 us, as long as a short path's whole
// verification.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// Runs `work` on the calling thread and offers it to up to `helpers` of the process's worker
/// threads (started on first use, as many as ever asked for; they sleep between calls). Returns
/// once the caller's run and the run of every worker that took the work have returned; a worker
/// takes it only while the caller has not finished its own run, so `work` must share what is left
/// to do (e.g. a counter) and return at once when nothing is. `work` must not throw. Safe to call
/// from many threads, and from inside `work`.
void runOnWorkers(const std::function<void()>& work, unsigned helpers);

/// Calls body(begin, end) for the chunks [0, chunk), [chunk, 2 chunk), ... of [0, n), in that
/// order of hand-out, on `threads` threads: the calling thread and up to threads - 1 workers
/// (runOnWorkers; 0: every hardware thread; never more than there are chunks). The first
/// exception a body throws stops the hand-out and is rethrown here once every thread has finished.
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
    runOnWorkers(work, threads - 1);
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace fastron
