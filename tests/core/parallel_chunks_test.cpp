// forEachChunk on the process's worker threads: every index once, from many callers at once, from
// inside a chunk, with exceptions; and the work really is shared.

#include "fastron/core/parallel_chunks.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace fastron {
namespace {

/// Runs forEachChunk over [0, n) and checks that every index was visited exactly once.
void expectEachIndexOnce(std::size_t n, std::size_t chunk, unsigned threads) {
  std::vector<std::atomic<int>> visits(n);
  forEachChunk(n, chunk, threads, [&](std::size_t begin, std::size_t end) {
    ASSERT_LT(begin, end);
    ASSERT_LE(end, n);
    ASSERT_LE(end - begin, chunk);
    for (std::size_t i = begin; i < end; ++i) visits[i].fetch_add(1);
  });
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(visits[i].load(), 1)
        << "index " << i << " of " << n << ", chunk " << chunk << ", threads " << threads;
  }
}

TEST(ForEachChunk, VisitsEveryIndexOnce) {
  for (const std::size_t n : {0, 1, 7, 8, 9, 1000}) {
    for (const std::size_t chunk : {1, 4, 64}) {
      for (const unsigned threads : {0u, 1u, 2u, 5u}) expectEachIndexOnce(n, chunk, threads);
    }
  }
}

TEST(ForEachChunk, ManyCallersAtOnceAndCallsFromInsideAChunk) {
  std::vector<std::jthread> callers;
  for (int c = 0; c < 4; ++c) {
    callers.emplace_back([] {
      for (int i = 0; i < 200; ++i) expectEachIndexOnce(97, 3, 3);
    });
  }
  callers.clear();  // joins
  // A chunk that spreads its own work: the caller always takes part, so nothing waits forever.
  std::atomic<std::size_t> inner{0};
  forEachChunk(8, 1, 3, [&](std::size_t, std::size_t) {
    forEachChunk(50, 2, 3, [&](std::size_t begin, std::size_t end) { inner += end - begin; });
  });
  EXPECT_EQ(inner.load(), 8u * 50u);
}

TEST(ForEachChunk, RethrowsTheFirstExceptionAndStaysUsable) {
  // Chunks of 50 us, so that the exception at chunk 10 comes long before chunk 500 would be
  // handed out (trivial chunks can all be handed out while the thread with chunk 10 is
  // descheduled).
  std::atomic<std::size_t> after{0};
  EXPECT_THROW(forEachChunk(1000, 1, 2,
                            [&](std::size_t begin, std::size_t) {
                              if (begin == 10) throw std::runtime_error("chunk 10");
                              std::this_thread::sleep_for(std::chrono::microseconds(50));
                              if (begin >= 500) ++after;
                            }),
               std::runtime_error);
  EXPECT_EQ(after.load(), 0u) << "the hand-out stops after the exception";
  expectEachIndexOnce(100, 4, 2);
}

TEST(ForEachChunk, SharesLongWorkWithAWorker) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one hardware thread";
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> elsewhere{0};
  forEachChunk(20, 1, 2, [&](std::size_t, std::size_t) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (std::this_thread::get_id() != caller) ++elsewhere;
  });
  EXPECT_GT(elsewhere.load(), 0) << "a worker took part in 40 ms of work";
}

}  // namespace
}  // namespace fastron
