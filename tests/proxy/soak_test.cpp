// Soak: Fastron as it runs on a robot for hours. Two threads query model snapshots (single,
// batch and edge queries) while the background thread updates the model and a third thread moves
// the boxes and replaces the oracle's scene. Every answer is checked against the snapshot it came
// from, and the process's memory is measured after warm-up and at the end.
//
// FASTRON_SOAK_QUERIES sets the number of queries (default: 10^7, 10^5 under sanitizers); the
// long run of docs/reliability.md is FASTRON_SOAK_QUERIES=1000000000.

#include <gtest/gtest.h>
#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "fastron/core/active_learning.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_features.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron {
namespace {

std::size_t queriesToRun() {
#ifdef FASTRON_SANITIZED
  std::size_t queries = 100'000;
#else
  std::size_t queries = 10'000'000;
#endif
  if (const char* text = std::getenv("FASTRON_SOAK_QUERIES")) queries = std::stoull(text);
  return queries;
}

/// Resident memory of this process in kB (VmRSS), 0 where /proc is missing, after the free pages
/// of the heap went back to the system (else it follows the largest heap the process ever had).
std::size_t residentKilobytes() {
  ::malloc_trim(0);
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stoull(line.substr(6));
  }
  return 0;
}

/// Heap bytes in use now (glibc's count over all arenas), in kB: what a leak would grow. Freed
/// blocks that glibc keeps in its per-thread caches count as in use: ctest runs this test with
/// those caches off (GLIBC_TUNABLES=glibc.malloc.tcache_count=0), else they fill slowly over a
/// long run and look like growth.
std::size_t heapKilobytes() {
  const struct mallinfo2 info = ::mallinfo2();
  return (info.uordblks + info.hblkhd) / 1024;
}

struct Memory {
  std::size_t resident = 0, heap = 0;
};

/// What a reader found wrong, if anything (checked on the main thread: gtest assertions in
/// other threads would not stop them).
struct ReaderResult {
  std::size_t queries = 0, snapshots = 0, wrong = 0;
  std::string firstWrong;
};

/// Queries snapshots until `done`, checking each answer against the snapshot it came from:
/// a single query's score equals the batch score of the same configuration (to float rounding:
/// the two paths sum in different orders), an edge's first collision is the first positive batch
/// score (the same path), the version never goes back, one version is one model, and the
/// snapshot's checksum still holds when the reader lets it go.
ReaderResult readSnapshots(const ProxyCollisionDetector& proxy, const JointLimits& limits,
                           std::uint64_t seed, const std::atomic<bool>& done,
                           std::atomic<std::size_t>& total) {
  ReaderResult result;
  Rng rng(seed);
  const auto wrong = [&](const std::string& what) {
    if (result.wrong++ == 0) result.firstWrong = what;
  };
  std::uint64_t lastVersion = 0;
  const Model* lastModel = nullptr;
  constexpr Eigen::Index kRows = 16;
  Configurations edge(kRows, static_cast<Eigen::Index>(limits.dim()));
  while (!done.load(std::memory_order_relaxed)) {
    const CalibratedModel snapshot = proxy.calibratedModel();
    const Model& model = *snapshot.model;
    if (snapshot.version < lastVersion) wrong("version went back");
    if (snapshot.version == lastVersion && &model != lastModel) wrong("one version, two models");
    if (&model != lastModel) ++result.snapshots;
    // Float sums of the two paths differ by a few float ulps of the largest partial sum.
    const double tolerance = 1e-5 * (model.weights().cwiseAbs().sum() + 1);
    lastVersion = snapshot.version;
    lastModel = &model;
    // A few rounds per snapshot: an edge between two random configurations, sampled densely.
    for (int round = 0; round < 8; ++round) {
      const Configurations ends = uniformConfigurations(limits, 2, rng);
      for (Eigen::Index i = 0; i < kRows; ++i) {
        const double t = static_cast<double>(i) / (kRows - 1);
        edge.row(i) = (1 - t) * ends.row(0) + t * ends.row(1);
      }
      const Eigen::VectorXd batch = model.scoreBatch(edge);
      Eigen::Index firstPositive = kRows;
      for (Eigen::Index i = 0; i < kRows; ++i) {
        if (std::abs(model.score(edge.row(i).data()) - batch[i]) > tolerance)
          wrong("a single score differs from the batch score");
        if (firstPositive == kRows && batch[i] > 0) firstPositive = i;
      }
      if (model.firstInCollision(edge) != static_cast<std::size_t>(firstPositive))
        wrong("the edge query disagrees with the batch scores");
      result.queries += 3 * kRows;
    }
    if (model.computeChecksum() != model.checksum()) wrong("a snapshot changed under its reader");
    total.fetch_add(8 * 3 * kRows, std::memory_order_relaxed);
  }
  return result;
}

TEST(Soak, QueriesUnderUpdatesAndSceneChanges) {
  const std::size_t queries = queriesToRun();
  Robot baxter = loadRobot("baxter");
  Scene scene = loadScene(dataDirectory() / "scenes" / "baxter_three_boxes.yaml");
  auto fcl = std::make_shared<FclChecker>(baxter, scene);
  ProxyParams params;
  params.train = defaultTrainParams(FeatureKind::Kinematic);
  params.train.maxSupportPoints = 3000;
  params.activeLearning.maxSamples = 300;
  params.labelThreads = 1;  // the readers have the other cores
  params.calibrationSamples = 300;
  ProxyCollisionDetector proxy(fcl, robotFeatures(baxter, FeatureKind::Kinematic), params);
  proxy.initialize(1500);

  std::atomic<bool> done{false};
  std::atomic<std::size_t> total{0};
  std::atomic<std::size_t> sceneChanges{0};
  ReaderResult a, b;
  std::vector<Memory> memory;  // kB
  proxy.startBackground({}, std::chrono::milliseconds(20));
  {
    const JointLimits limits = baxter.limits();
    std::jthread readerA([&] { a = readSnapshots(proxy, limits, 1, done, total); });
    std::jthread readerB([&] { b = readSnapshots(proxy, limits, 2, done, total); });
    std::jthread mover([&] {
      while (!done.load(std::memory_order_relaxed)) {
        scene.step();
        fcl->setScene(scene);
        ++sceneChanges;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    });
    // Memory at every tenth of the run; the first tenth is the warm-up. The run also lasts until
    // the updater has published two models (up to a minute): under the sanitizers the readers can
    // finish their queries before the first update does, and then nothing was soaked.
    for (std::size_t tenth = 1; tenth <= 10; ++tenth) {
      while (total.load() < queries / 10 * tenth)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      memory.push_back({residentKilobytes(), heapKilobytes()});
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (proxy.backgroundHealth().steps < 2 && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    done = true;
  }
  proxy.stopBackground();
  const BackgroundHealth health = proxy.backgroundHealth();

  // Growth after warm-up of the heap in use, as a share of the process's memory then, and of the
  // resident memory itself. The heap is judged by the least of the last three tenths: one sample
  // can fall inside an update that holds its working memory (Gram columns, the next model) for a
  // moment, while a leak raises every later sample.
  const auto before = static_cast<double>(std::max<std::size_t>(1, memory.front().resident));
  const std::size_t heapAtEnd = std::min({memory[7].heap, memory[8].heap, memory[9].heap});
  const double heapGrowth =
      (static_cast<double>(heapAtEnd) - static_cast<double>(memory.front().heap)) / before;
  const double residentGrowth = static_cast<double>(memory.back().resident) / before - 1;
  std::string heapTenths, residentTenths;
  for (const Memory& m : memory) {
    heapTenths += " " + std::to_string(m.heap);
    residentTenths += " " + std::to_string(m.resident);
  }
  std::printf(
      "soak: %zu queries on %zu + %zu snapshots, %llu updates, %llu faults, %zu scene changes, "
      "|S| %zu\n  heap in use after warm-up %zu kB, at the end %zu kB (least of the last three "
      "tenths, %+.2f%% of the process's "
      "memory); every tenth:%s\n  resident after warm-up %zu kB, at the end %zu kB (%+.2f%%); "
      "every tenth:%s\n",
      a.queries + b.queries, a.snapshots, b.snapshots,
      static_cast<unsigned long long>(health.steps), static_cast<unsigned long long>(health.faults),
      sceneChanges.load(), proxy.model()->supportCount(), memory.front().heap, heapAtEnd,
      100 * heapGrowth, heapTenths.c_str(), memory.front().resident, memory.back().resident,
      100 * residentGrowth, residentTenths.c_str());
  EXPECT_EQ(a.wrong, 0u) << a.firstWrong;
  EXPECT_EQ(b.wrong, 0u) << b.firstWrong;
  EXPECT_GE(a.queries + b.queries, queries);
  EXPECT_GE(health.steps, 1u);
  EXPECT_GT(a.snapshots + b.snapshots, 2u);  // the readers saw new models arrive
#ifndef FASTRON_SANITIZED
  // The sanitizers keep freed memory in quarantine: memory is judged in plain builds only.
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables != nullptr && std::string(tunables).find("tcache_count=0") != std::string::npos) {
    EXPECT_LT(heapGrowth, 0.01);
  }
#endif
}

}  // namespace
}  // namespace fastron
