#include "helper_thread.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

namespace fastron::detail {
namespace {

void pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}

/// A round whose helper kept the calling thread waiting longer than this for its chunk is late: a
/// chunk that shares a round fairly ends within tens of microseconds of the calling thread's own.
/// After kLateRounds late rounds the helper is let go for the rest of the session. Once in a
/// while the virtual machine stops a core for longer (a self-collision training of 7648
/// iterations on 40000 points met 0 to 2 such rounds in each of 16 trainings); a helper that
/// another busy thread preempts again and again is late every few milliseconds, and each late
/// round costs at most a time slice of the scheduler.
constexpr std::chrono::microseconds kPatience{200};
constexpr std::size_t kLateRounds = 4;

/// A round's work as the helper reads it.
struct Round {
  void (*body)(void*, std::size_t);
  void* context;
};

// The state of the current round in one word, so that a chunk is claimed with one
// compare-and-swap that also checks the round: bits 32-63 the round's number, 16-31 the end of
// the chunks left, 0-15 their start. The owner takes chunks from the start and the helper from
// the end, so that with two chunks each core gets the same rows round after round and keeps them
// in its own cache (both taking from the start measured the same within this machine's noise,
// docs/performance.md). A thread that read an older round's state fails its claim instead of
// running a chunk of the new round with the old body.
std::uint64_t stateOf(std::uint64_t round, std::size_t chunks) {
  return round << 32 | static_cast<std::uint64_t>(chunks) << 16;
}
std::size_t firstLeft(std::uint64_t state) {
  return state & 0xffff;
}
std::size_t endLeft(std::uint64_t state) {
  return (state >> 16) & 0xffff;
}
constexpr std::uint64_t kOneFromStart = 1, kOneFromEnd = std::uint64_t{1} << 16;

class Helper {
 public:
  Helper() : thread_([this] { serve(); }) {}
  ~Helper() {
    {
      const std::lock_guard lock(mutex_);
      quit_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }
  Helper(const Helper&) = delete;
  Helper& operator=(const Helper&) = delete;

  std::mutex& owner() { return owner_; }

  void begin() {
    {
      const std::lock_guard lock(mutex_);
      active_.store(true, std::memory_order_relaxed);
    }
    wake_.notify_one();
  }
  void end() { active_.store(false, std::memory_order_release); }

  /// What became of a round the helper was offered.
  struct Outcome {
    bool shared = false;  ///< the helper ran a chunk
    bool late = false;    ///< it kept the calling thread waiting past kPatience
  };

  /// Runs the round's chunks here and on the helper.
  Outcome run(std::size_t chunks, Round round) {
    round_.store(round.body, std::memory_order_relaxed);
    context_.store(round.context, std::memory_order_relaxed);
    done_.store(0, std::memory_order_relaxed);
    state_.store(stateOf(++rounds_, chunks), std::memory_order_release);
    std::size_t ranHere = 0;
    while (claimAndRun(true)) ++ranHere;
    const auto waitStart = std::chrono::steady_clock::now();
    bool late = false;
    for (unsigned spins = 1; done_.load(std::memory_order_acquire) != chunks; ++spins) {
      if (late) {
        std::this_thread::yield();  // the helper may need this core to finish
      } else if (spins % 64 != 0) {
        pause();
      } else {
        late = std::chrono::steady_clock::now() - waitStart > kPatience;
      }
    }
    return {ranHere < chunks, late};
  }

 private:
  /// Runs one chunk of the current round if one is left, the first left for the owner and the
  /// last for the helper; false when none is.
  bool claimAndRun(bool owner) {
    std::uint64_t state = state_.load(std::memory_order_acquire);
    for (;;) {
      if (firstLeft(state) >= endLeft(state)) return false;
      const std::size_t c = owner ? firstLeft(state) : endLeft(state) - 1;
      // Read before the claim: a successful claim means the round is not over, so these are
      // its body and context (run() writes the next round's only after this one's chunks ran).
      const auto body = round_.load(std::memory_order_relaxed);
      void* const context = context_.load(std::memory_order_relaxed);
      const std::uint64_t claimed = owner ? state + kOneFromStart : state - kOneFromEnd;
      if (state_.compare_exchange_weak(state, claimed, std::memory_order_acq_rel,
                                       std::memory_order_acquire)) {
        body(context, c);
        done_.fetch_add(1, std::memory_order_release);
        return true;
      }
    }
  }

  void serve() {
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return quit_ || active_.load(std::memory_order_relaxed); });
      if (quit_) return;
      lock.unlock();
      while (active_.load(std::memory_order_acquire)) {
        if (!claimAndRun(false)) pause();
      }
      lock.lock();
    }
  }

  std::mutex owner_;  // held by the session the helper serves
  std::mutex mutex_;
  std::condition_variable wake_;
  bool quit_ = false;                // under mutex_
  std::atomic<bool> active_{false};  // a session is running: spin, do not sleep
  std::atomic<std::uint64_t> state_{0};
  std::atomic<void (*)(void*, std::size_t)> round_{nullptr};
  std::atomic<void*> context_{nullptr};
  std::atomic<std::size_t> done_{0};
  std::uint64_t rounds_ = 0;  // the owner's count
  std::thread thread_;        // last: starts once the members above exist
};

Helper& helper() {
  static Helper instance;
  return instance;
}

}  // namespace

HelperSession::HelperSession(bool wanted) {
  static const bool severalCores = std::thread::hardware_concurrency() >= 2;
  if (!wanted || !severalCores) return;
  Helper& h = helper();
  if (!h.owner().try_lock()) return;
  h.begin();
  helped_ = true;
}

HelperSession::~HelperSession() {
  release();
}

void HelperSession::release() {
  if (!helped_) return;
  helper().end();
  helper().owner().unlock();
  helped_ = false;
}

bool HelperSession::runChunks(std::size_t chunks, void (*body)(void*, std::size_t), void* context) {
  if (!helped_) {
    for (std::size_t c = 0; c < chunks; ++c) body(context, c);
    return false;
  }
  const Helper::Outcome outcome = helper().run(chunks, {body, context});
  // A helper that keeps us waiting again and again is most likely preempted by another busy
  // thread of the process or of the machine: every later round would wait for it again, so the
  // rest of the session runs on this thread alone.
  lateRounds_ += static_cast<std::size_t>(outcome.late);
  if (lateRounds_ == kLateRounds) release();
  return outcome.shared;
}

}  // namespace fastron::detail
