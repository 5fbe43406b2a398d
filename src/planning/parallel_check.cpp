#include "fastron/planning/parallel_check.h"

#include <algorithm>
#include <atomic>
#include <chrono>

#include "fastron/core/parallel_chunks.h"

namespace fastron {
namespace {

/// What a state to check is: a waypoint (index = waypoint) or an interior state of edge `index`.
struct Item {
  std::size_t index;
  bool waypoint;
};

// With threads = 0, the first kProbe states are checked on the calling thread and timed; the
// rest go to every core when they would take at least kParallelWork at that rate, else stay on the
// calling thread. A worker wakes in 12-40 us and meets the checker's data cold in its caches, and
// where a background model update owns the other core it only takes turns with it: on Baxter
// among boxes (0.7-1 us a state, paths of 100-400 states) two threads verified 1.35 times faster
// in `bench plan` and no faster in `fastron demo`; on the mesh Panda (about 10 us a state) 1.6-1.7
// times faster in `bench motion-bench` (docs/log/2026-11-23-motion-bench-panda-meshes-and-srdf.md,
// "Verification on every core").
constexpr std::size_t kProbe = 16;
constexpr std::chrono::microseconds kParallelWork{250};
// States handed to a thread at a time: few, so that the bisection order is kept roughly, and
// enough that a checker's batch path (one world read, one scratch lease) pays.
constexpr std::size_t kChunk = 8;

/// checkPathParallel for a checker that proves motions free (provesMotionsFree): the first
/// waypoint, then each edge as one motion (its states between the waypoints, its end included),
/// edges handed out one at a time. The motion check decides its end waypoint as well: a checker
/// that proves motions free looks at the end first (certifiedMotionCheck), so checking the
/// waypoints in a batch before placed each of them once more (the mesh Panda's paths:
/// BM_VerifyPath, docs/planning.md). An edge whose end collides has its interior states checked one
/// by one, as motionCollision stops at that end; an edge whose interior collides has its end
/// checked alone.
PathCheck checkByMotions(const CollisionChecker& checker, const JointPath& path, double resolution,
                         unsigned threads) {
  const std::size_t dim = checker.dof();
  const std::size_t edges = path.size() - 1;
  std::vector<std::uint8_t> waypointHit(path.size());
  const auto collides = [&](const Eigen::VectorXd& q) -> std::uint8_t {
    return checker.inCollision(std::span<const double>(q.data(), dim)) ? 1 : 0;
  };
  waypointHit[0] = collides(path[0]);
  std::vector<std::uint8_t> edgeHit(edges);
  const auto checkEdge = [&](std::size_t e) {
    const std::size_t n = segmentCount(path[e], path[e + 1], resolution);
    const std::size_t hit =
        checker.motionCollision(path[e].data(), path[e + 1].data(), n).collidingState;
    if (hit == 0) return;
    if (hit != n) {
      edgeHit[e] = 1;
      waypointHit[e + 1] = collides(path[e + 1]);
      return;
    }
    waypointHit[e + 1] = 1;
    std::vector<double> states;  // rows 1..n-1: the interior
    motionStates(path[e].data(), path[e + 1].data(), dim, n, states);
    edgeHit[e] = checker.firstInCollision(states.data() + dim, n - 1) < n - 1 ? 1 : 0;
  };
  std::size_t first = 0;  // the edges checked before the hand-out
  if (threads == 0 && edges > 0) {
    const auto began = std::chrono::steady_clock::now();
    checkEdge(0);
    first = 1;
    const auto rest = (std::chrono::steady_clock::now() - began) * static_cast<double>(edges - 1);
    threads = rest >= kParallelWork ? 0 : 1;
  }
  forEachChunk(edges - first, 1, threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t e = first + begin; e < first + end; ++e) checkEdge(e);
  });
  PathCheck check;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (waypointHit[i] != 0) check.invalidWaypoints.push_back(i);
  }
  for (std::size_t e = 0; e < edges; ++e) {
    if (edgeHit[e] != 0) check.invalidEdges.push_back(e);
  }
  return check;
}

}  // namespace

PathCheck checkPathParallel(const CollisionChecker& checker, const JointPath& path,
                            double resolution, unsigned threads) {
  PathCheck check;
  if (path.empty()) {
    check.invalidWaypoints.push_back(0);
    return check;
  }
  const std::size_t dim = checker.dof();
  checkWaypointSizes(path, dim);
  // Whole edges wherever the checker proves motions free, short paths too: a short path's few
  // edges leave a core idle that the states' hand-out would keep busy, but since the looks got
  // cheaper (2026-12-01) the mesh Panda's MotionBenchMaker paths verify as fast by edges.
  if (checker.provesMotionsFree()) return checkByMotions(checker, path, resolution, threads);
  const std::size_t edges = path.size() - 1;
  // Interior states of each edge in bisection order (motionStates' rows 1..n-1: row 0 is the
  // edge's end, a waypoint checked as such).
  std::vector<std::vector<double>> interior(edges);
  std::size_t deepest = 0;
  for (std::size_t e = 0; e < edges; ++e) {
    const std::size_t n = segmentCount(path[e], path[e + 1], resolution);
    motionStates(path[e].data(), path[e + 1].data(), dim, n, interior[e]);
    deepest = std::max(deepest, n - 1);
  }
  // The states in that order, one after the other, so that a chunk is one batch for the checker.
  std::vector<Item> order;
  std::vector<double> states;
  const auto add = [&](const double* q, Item item) {
    order.push_back(item);
    states.insert(states.end(), q, q + dim);
  };
  for (std::size_t i = 0; i < path.size(); ++i) add(path[i].data(), {i, true});
  for (std::size_t level = 1; level <= deepest; ++level) {
    for (std::size_t e = 0; e < edges; ++e) {
      if (level * dim < interior[e].size()) add(interior[e].data() + level * dim, {e, false});
    }
  }

  std::vector<std::atomic<bool>> waypointHit(path.size()), edgeHit(edges);
  const auto settled = [&](std::size_t k) {  // a state of an edge already found invalid
    return !order[k].waypoint && edgeHit[order[k].index].load(std::memory_order_relaxed);
  };
  const auto checkStates = [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end;) {
      if (settled(k)) {
        ++k;
        continue;
      }
      const std::size_t hit = k + checker.firstInCollision(states.data() + k * dim, end - k);
      if (hit == end) break;
      (order[hit].waypoint ? waypointHit : edgeHit)[order[hit].index].store(
          true, std::memory_order_relaxed);
      k = hit + 1;
    }
  };
  std::size_t first = 0;  // the states checked before the hand-out (at least 1: a waypoint)
  if (threads == 0) {
    first = std::min(order.size(), kProbe);
    const auto began = std::chrono::steady_clock::now();
    checkStates(0, first);
    const auto rest = (std::chrono::steady_clock::now() - began) *
                      static_cast<double>(order.size() - first) / static_cast<double>(first);
    threads = rest >= kParallelWork ? 0 : 1;  // 0: every core
  }
  forEachChunk(order.size() - first, kChunk, threads, [&](std::size_t begin, std::size_t end) {
    checkStates(first + begin, first + end);
  });

  for (std::size_t i = 0; i < path.size(); ++i) {
    if (waypointHit[i].load()) check.invalidWaypoints.push_back(i);
  }
  for (std::size_t e = 0; e < edges; ++e) {
    if (edgeHit[e].load()) check.invalidEdges.push_back(e);
  }
  return check;
}

}  // namespace fastron
