#include "fastron/proxy/labelling.h"

#include <algorithm>
#include <exception>
#include <string>

#include "fastron/proxy/parallel_chunks.h"

namespace fastron {
namespace {

constexpr std::size_t kChunk = 16;  // rows handed out at a time: balances uneven check costs

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
  forEachChunk(n, kChunk, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (guard.stop.stop_requested()) throw LabellingStopped("labelling stopped");
      if (timed && std::chrono::steady_clock::now() > guard.deadline)
        throw fault("passed its labelling deadline (" + std::to_string(n) + " configurations)");
      const std::span<const double> row(q.data() + i * d, d);
      try {
        labels[i] = labelOf(checker.inCollision(row));
        const bool repeated = stride != 0 && i % stride == 0 && i / stride < guard.repeatedRows;
        if (repeated && labels[i] != labelOf(checker.inCollision(row)))
          throw fault("gave two different answers for the same configuration (row " +
                      std::to_string(i) + ")");
      } catch (const OracleFault&) {
        throw;
      } catch (const std::exception& e) {
        throw fault(std::string("failed: ") + e.what());
      }
    }
  });
  return labels;
}

}  // namespace fastron
