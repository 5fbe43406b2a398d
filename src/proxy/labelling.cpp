#include "fastron/proxy/labelling.h"

#include <algorithm>
#include <exception>
#include <string>

#include "fastron/core/parallel_chunks.h"

namespace fastron {
namespace {

constexpr std::size_t kChunk = 16;  // rows handed out at a time: balances uneven check costs
// A check at most this long lets the rest of its chunk go in one call: at most about 0.3 ms
// between two looks at the stop and the deadline.
constexpr std::chrono::microseconds kQuickCall{20};

std::int8_t labelOf(bool inCollision) {
  return inCollision ? std::int8_t{1} : std::int8_t{-1};
}

}  // namespace

Labels labelConfigurations(const CollisionChecker& checker, const Configurations& q,
                           unsigned threads, const LabelGuard& guard) {
  const auto n = static_cast<std::size_t>(q.rows());
  const auto d = static_cast<std::size_t>(q.cols());
  const std::size_t stride =
      guard.repeatedRows == 0 ? 0 : std::max<std::size_t>(1, n / guard.repeatedRows);
  const auto fault = [&](const std::string& what) {
    return OracleFault("oracle '" + checker.name() + "' " + what);
  };
  const bool timed = guard.deadline != std::chrono::steady_clock::time_point::max();
  Labels labels(n);
  // Labels the rows [begin, end) with one call of the checker.
  const auto labelRun = [&](std::size_t begin, std::size_t end) {
    if (guard.stop.stop_requested()) throw LabellingStopped("labelling stopped");
    if (timed && std::chrono::steady_clock::now() > guard.deadline)
      throw fault("passed its labelling deadline (" + std::to_string(n) + " configurations)");
    std::uint8_t hits[kChunk];
    try {
      checker.inCollisionEach(q.data() + begin * d, end - begin, hits);
      for (std::size_t i = begin; i < end; ++i) {
        labels[i] = labelOf(hits[i - begin] != 0);
        const bool repeated = stride != 0 && i % stride == 0 && i / stride < guard.repeatedRows;
        if (repeated && labels[i] != labelOf(checker.inCollision({q.data() + i * d, d})))
          throw fault("gave two different answers for the same configuration (row " +
                      std::to_string(i) + ")");
      }
    } catch (const OracleFault&) {
      throw;
    } catch (const std::exception& e) {
      throw fault(std::string("failed: ") + e.what());
    }
  };
  forEachChunk(n, kChunk, threads, [&](std::size_t begin, std::size_t end) {
    // The chunk's first row alone; when that took less than kQuickCall, the rest in one call
    // (one read of the checker's world and one scratch lease for them all: leased per row, two
    // FCL labelling threads contended for them and labelled no faster than one). A slow oracle
    // keeps one row per call, so that the stop and the deadline are seen between its calls.
    const auto began = std::chrono::steady_clock::now();
    labelRun(begin, begin + 1);
    if (std::chrono::steady_clock::now() - began < kQuickCall) {
      if (begin + 1 < end) labelRun(begin + 1, end);
      return;
    }
    for (std::size_t i = begin + 1; i < end; ++i) labelRun(i, i + 1);
  });
  return labels;
}

}  // namespace fastron
