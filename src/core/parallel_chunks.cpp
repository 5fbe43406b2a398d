#include "fastron/core/parallel_chunks.h"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <vector>

namespace fastron {
namespace {

constexpr std::chrono::microseconds kWatch{100};

/// One call of runOnWorkers: the work and how many workers may still take it.
struct Offer {
  const std::function<void()>* work;
  unsigned open;         ///< workers that may still take it
  unsigned running = 0;  ///< workers running it now
};

class Workers {
 public:
  ~Workers() {
    {
      const std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  void run(const std::function<void()>& work, unsigned helpers) {
    Offer offer{&work, helpers};
    {
      const std::lock_guard lock(mutex_);
      while (threads_.size() < helpers) threads_.emplace_back([this] { serve(); });
      offers_.push_back(&offer);
      offered_.fetch_add(1, std::memory_order_release);
    }
    for (unsigned i = 0; i < helpers; ++i) wake_.notify_one();
    work();
    std::unique_lock lock(mutex_);
    // No worker takes the offer from now on; wait for those that did.
    if (offer.open > 0) {
      std::erase(offers_, &offer);
      offered_.fetch_sub(1, std::memory_order_relaxed);
    }
    finished_.wait(lock, [&] { return offer.running == 0; });
  }

 private:
  void serve() {
    std::unique_lock lock(mutex_);
    while (true) {
      if (offers_.empty() && !stopping_) {
        // Work comes in bursts (an update labels its support set, its new points and its
        // calibration points one after the other): watch for a new offer for a while before
        // sleeping, since waking from sleep costs about 12 us.
        lock.unlock();
        const auto until = std::chrono::steady_clock::now() + kWatch;
        while (offered_.load(std::memory_order_acquire) == 0 &&
               std::chrono::steady_clock::now() < until) {
          std::this_thread::yield();
        }
        lock.lock();
      }
      wake_.wait(lock, [&] { return stopping_ || !offers_.empty(); });
      if (stopping_) return;
      Offer* offer = offers_.front();
      if (--offer->open == 0) {
        offers_.pop_front();
        offered_.fetch_sub(1, std::memory_order_relaxed);
      }
      ++offer->running;
      lock.unlock();
      (*offer->work)();
      lock.lock();
      --offer->running;
      finished_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::deque<Offer*> offers_;            ///< offers with workers still wanted, oldest first
  std::atomic<std::size_t> offered_{0};  ///< offers_.size(), read without the lock
  std::vector<std::thread> threads_;
  bool stopping_ = false;
};

}  // namespace

void runOnWorkers(const std::function<void()>& work, unsigned helpers) {
  static Workers workers;
  if (helpers == 0) {
    work();
    return;
  }
  workers.run(work, helpers);
}

}  // namespace fastron
