#pragma once
// A second core for loops of short rounds: Algorithm 1's iterations take a few microseconds each,
// too short to wake a sleeping thread per iteration (12-40 us on this project's machine) but long
// enough to share: a thread spinning between rounds takes a piece of each one. Private to core.

#include <cstddef>

namespace fastron::detail {

/// While it lives, the process's helper thread (one, started at first use) spins waiting for
/// rounds of work and takes chunks of each round beside the calling thread: the calling thread
/// takes them from the first, the helper from the last, so that with two chunks each keeps the
/// same rows in its cache round after round. Only one session holds the helper at a time: a
/// session that finds it held, or is not wanted, or runs on a single-core machine, runs every
/// chunk on the calling thread, and so does the rest of a session whose helper kept the calling
/// thread waiting over 200 us for its chunk in 4 rounds (preempted: a busy machine). Rounds are run
/// from the thread that created the session.
class HelperSession {
 public:
  explicit HelperSession(bool wanted);
  ~HelperSession();
  HelperSession(const HelperSession&) = delete;
  HelperSession& operator=(const HelperSession&) = delete;

  /// Whether the helper takes part in this session's next round.
  bool helped() const { return helped_; }

  /// Runs body(c) for every chunk c in [0, chunks) (at most 65535), on this thread and the
  /// helper, and returns when every chunk has run: true when the helper ran some of them.
  /// `body` must not throw.
  template <class Body>
  bool run(std::size_t chunks, Body& body) {
    return runChunks(
        chunks, [](void* context, std::size_t c) { (*static_cast<Body*>(context))(c); }, &body);
  }

 private:
  bool runChunks(std::size_t chunks, void (*body)(void*, std::size_t), void* context);
  /// Lets the helper go (it sleeps until the next session); later rounds run on this thread.
  void release();

  bool helped_ = false;
  std::size_t lateRounds_ = 0;  // rounds whose helper kept this thread waiting (helper_thread.cpp)
};

}  // namespace fastron::detail
