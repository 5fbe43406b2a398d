// Micro-benchmarks of the core: training time against N and d, query time against |S| and d.
// The vectorised float path is measured against a plain double loop in the same run; compare
// them as ratios (scripts/bench_table.py does this), never as absolute numbers across machines.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "fastron/baselines/original_fastron_query.h"
#include "fastron/core/model.h"
#include "fastron/core/parallel_chunks.h"
#include "fastron/core/reference_trainer.h"
#include "fastron/core/trainer.h"
#include "test_worlds.h"

namespace fastron {
namespace {

// The paper's gamma for each dimension: 30 (2-DOF), 10 (4-DOF), 5 (6, 7-DOF).
double paperGamma(std::size_t d) {
  return d <= 2 ? 30 : d <= 4 ? 10 : 5;
}

// Balls filling a sizeable share of [-1, 1]^d, so both classes are present at every d. Above 7
// dimensions (standing for task-space features, which depend on 7 joints) the balls are in the
// first 7 coordinates: in [-1, 1]^27 a ball world is all one class.
Labels ballLabels(const Configurations& q, std::size_t d) {
  const std::size_t k = std::min<std::size_t>(d, 7);
  return test::BallWorld::random(k, 6, 0.35 * std::sqrt(static_cast<double>(k)), 2)
      .label(q.leftCols(static_cast<Eigen::Index>(k)));
}

/// The training data and settings of BM_Train and BM_TrainReference for N = range(0) points in
/// d = range(1) dimensions: uniform points, ball labels, the paper's gamma, no caps in the way.
/// terms = range(2): 1 gives the kernel a term per 3 features beside the whole vector's (share
/// 0.5, the task-space default), 0 one term.
struct TrainingCase {
  std::size_t d;
  Configurations q;
  Labels y;
  TrainParams params;
};

TrainingCase trainingCase(const benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const auto d = static_cast<std::size_t>(state.range(1));
  // Values a float holds exactly: the features a Trainer stores (trainer.cpp), so that the
  // reference trains on the same ones.
  TrainingCase c{d, test::uniformPoints(n, d, 1).cast<float>().cast<double>(), {}, {}};
  c.y = ballLabels(c.q, d);
  c.params.kernel.gamma = paperGamma(d);
  if (state.range(2) != 0) {
    c.params.kernel.block = 3;
    c.params.kernel.wholeShare = 0.5;
  }
  c.params.maxIterations = 1'000'000;
  c.params.maxSupportPoints = n;
  return c;
}

void train(benchmark::State& state, bool floatColumns) {
  TrainingCase c = trainingCase(state);
  c.params.floatGramColumns = floatColumns;
  UpdateReport report;
  for (auto _ : state) {
    state.PauseTiming();  // Algorithm 1 only, as BM_TrainReference
    Trainer trainer(JointLimits::unitBox(c.d), c.params);
    trainer.addPoints(c.q, c.y);
    state.ResumeTiming();
    report = trainer.update();
    benchmark::DoNotOptimize(trainer.weights().data());
  }
  state.counters["support"] = static_cast<double>(report.supportCount);
  state.counters["iterations"] = static_cast<double>(report.iterations);
  state.counters["gram_columns"] = static_cast<double>(report.gramColumnsComputed);
}

void BM_Train(benchmark::State& state) {
  train(state, true);
}
BENCHMARK(BM_Train)
    ->ArgsProduct({{1000, 2000, 5000, 10000, 20000}, {2, 4, 7}, {0}})
    ->ArgsProduct({{8000}, {7, 9, 15, 18, 27}, {0}})
    ->ArgsProduct({{8000}, {9, 12, 15, 18, 27}, {1}})
    ->Args({5000, 3, 0})
    ->Args({5000, 5, 0})
    ->Args({5000, 6, 0})
    ->ArgNames({"N", "d", "terms"})
    ->Unit(benchmark::kMillisecond);

// Algorithm 1 with double Gram columns (TrainParams::floatGramColumns false) where BM_Train's
// are float: a rational-quadratic kernel of up to 12 features.
void BM_TrainDoubleColumns(benchmark::State& state) {
  train(state, false);
}
BENCHMARK(BM_TrainDoubleColumns)
    ->ArgsProduct({{8000}, {7, 9, 15, 18, 27}, {0}})
    ->ArgsProduct({{3000, 8000}, {12, 15, 18, 27}, {1}})
    ->ArgNames({"N", "d", "terms"})
    ->Unit(benchmark::kMillisecond);

// Algorithm 1 on threads = range(3) threads (Trainer::update(threads): each iteration's Gram
// column and F update split with a helper thread), against range(3) = 1 in the same run. N 3000
// is the size of a bench changing 7dof-3boxes update (2500 new points beside |S| about 400).
void BM_TrainOnThreads(benchmark::State& state) {
  const TrainingCase c = trainingCase(state);
  const auto threads = static_cast<unsigned>(state.range(3));
  UpdateReport report;
  for (auto _ : state) {
    state.PauseTiming();
    Trainer trainer(JointLimits::unitBox(c.d), c.params);
    trainer.addPoints(c.q, c.y);
    state.ResumeTiming();
    report = trainer.update(threads);
    benchmark::DoNotOptimize(trainer.weights().data());
  }
  state.counters["support"] = static_cast<double>(report.supportCount);
  state.counters["iterations"] = static_cast<double>(report.iterations);
}
BENCHMARK(BM_TrainOnThreads)
    ->ArgsProduct({{3000, 8000}, {7}, {0}, {1, 2}})
    ->ArgsProduct({{1500, 3000, 8000, 20000}, {12}, {1}, {1, 2}})
    ->ArgNames({"N", "d", "terms", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// An update's new points (Trainer::addPoints: their features, and F from the current weights)
// after Algorithm 1 trained on N = range(0) points in d = range(1) features with point terms: the
// 2000 active-learning points of an update, on threads = range(2) threads (forEachChunk, as
// ProxyCollisionDetector spreads them).
void BM_AddPoints(benchmark::State& state) {
  TrainingCase c = trainingCase(state);
  c.params.kernel.gamma = 100;  // the narrow kernel of bench changing's accurate setting
  c.params.kernel.block = 3;
  c.params.kernel.wholeShare = 0.5;
  c.params.beta = 10;
  Trainer trained(JointLimits::unitBox(c.d), c.params);
  trained.addPoints(c.q, c.y);
  trained.update();
  const Configurations fresh = test::uniformPoints(2000, c.d, 3);
  const Labels labels = ballLabels(fresh, c.d);
  const auto threads = static_cast<unsigned>(state.range(2));
  const ChunkRunner onThreads = [threads](std::size_t n, std::size_t chunk, const auto& body) {
    forEachChunk(n, chunk, threads, body);
  };
  for (auto _ : state) {
    state.PauseTiming();
    Trainer trainer = trained;
    state.ResumeTiming();
    trainer.addPoints(fresh, labels, onThreads);
    benchmark::DoNotOptimize(trainer.hypothesis().data());
  }
  state.counters["support"] = static_cast<double>(trained.supportCount());
}
BENCHMARK(BM_AddPoints)
    ->ArgsProduct({{3000}, {12}, {1, 2}})
    ->ArgNames({"N", "d", "threads"})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

// The same training with the plain scalar Algorithm 1 (reference_trainer.h): the baseline of
// BM_Train, measured in the same run. d = 9-27 stands for task-space features (3 coordinates of
// 3-9 control points).
void BM_TrainReference(benchmark::State& state) {
  const TrainingCase c = trainingCase(state);
  UpdateReport report;
  for (auto _ : state) {
    const ReferenceTraining result = trainReference(c.q, c.y, c.params);
    report = result.report;
    benchmark::DoNotOptimize(result.alpha.data());
  }
  state.counters["support"] = static_cast<double>(report.supportCount);
  state.counters["iterations"] = static_cast<double>(report.iterations);
}
BENCHMARK(BM_TrainReference)
    ->ArgsProduct({{8000}, {7, 9, 15, 18, 27}, {0}})
    ->ArgsProduct({{8000}, {9, 12, 15, 18, 27}, {1}})
    ->ArgNames({"N", "d", "terms"})
    ->Unit(benchmark::kMillisecond);

// A model with |S| random support points and weights: query cost depends only on |S| and d.
Model randomModel(std::size_t support, std::size_t d, KernelType type) {
  const Configurations s = test::uniformPoints(support, d, 3);
  const Eigen::VectorXd w = Eigen::VectorXd::Random(static_cast<Eigen::Index>(support));
  return {FeatureMap::jointScaling(JointLimits::unitBox(d)), {type, paperGamma(d)}, s, w};
}

constexpr std::size_t kQueries = 1024;

template <KernelType type>
void BM_QueryFloat(benchmark::State& state) {
  const auto support = static_cast<std::size_t>(state.range(0));
  const auto d = static_cast<std::size_t>(state.range(1));
  const Model model = randomModel(support, d, type);
  const Configurations q = test::uniformPoints(kQueries, d, 4);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(model.score(q.row(static_cast<Eigen::Index>(i)).data()));
    i = (i + 1) % kQueries;
  }
}

// The baseline: the kernel sum as a plain loop over row-major double support points.
void BM_QueryPlainDouble(benchmark::State& state) {
  const auto support = static_cast<std::size_t>(state.range(0));
  const auto d = static_cast<std::size_t>(state.range(1));
  const Model model = randomModel(support, d, KernelType::RationalQuadratic);
  const Configurations s = model.supportConfigurations();  // row-major copy
  const double* w = model.weights().data();
  const double halfGamma = 0.5 * model.kernel().gamma;
  const Configurations q = test::uniformPoints(kQueries, d, 4);
  std::size_t i = 0;
  for (auto _ : state) {
    const double* x = q.row(static_cast<Eigen::Index>(i)).data();
    double f = 0;
    for (std::size_t k = 0; k < support; ++k) {
      double r2 = 0;
      for (std::size_t j = 0; j < d; ++j) {
        const double diff = s.data()[k * d + j] - x[j];
        r2 += diff * diff;
      }
      const double t = 1 + halfGamma * r2;
      f += w[k] / (t * t);
    }
    benchmark::DoNotOptimize(f);
    i = (i + 1) % kQueries;
  }
}

// The original Fastron C++'s query (Fastron::eval of ucsdarclab/fastron, re-implemented): Eigen
// arrays over the support points in double, one query at a time.
void BM_QueryOriginalFastron(benchmark::State& state) {
  const auto support = static_cast<std::size_t>(state.range(0));
  const auto d = static_cast<std::size_t>(state.range(1));
  const OriginalFastronQuery original(randomModel(support, d, KernelType::RationalQuadratic));
  const Configurations q = test::uniformPoints(kQueries, d, 4);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(original.inCollision(q.row(static_cast<Eigen::Index>(i)).data()));
    i = (i + 1) % kQueries;
  }
}

void BM_QueryBatch(benchmark::State& state) {
  const auto support = static_cast<std::size_t>(state.range(0));
  const auto d = static_cast<std::size_t>(state.range(1));
  const Model model = randomModel(support, d, KernelType::RationalQuadratic);
  const Configurations q = test::uniformPoints(kQueries, d, 4);
  std::vector<double> out(kQueries);
  for (auto _ : state) {
    model.scoreBatch(q.data(), kQueries, out.data());
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kQueries));
}

void queryArgs(benchmark::internal::Benchmark* b) {
  b->ArgsProduct({{100, 500, 1000, 2000, 5000}, {2, 4, 7}})->ArgNames({"S", "d"});
}
BENCHMARK(BM_QueryFloat<KernelType::RationalQuadratic>)->Apply(queryArgs);
BENCHMARK(BM_QueryFloat<KernelType::Gaussian>)->Apply(queryArgs);
BENCHMARK(BM_QueryPlainDouble)->Apply(queryArgs);
BENCHMARK(BM_QueryOriginalFastron)->Apply(queryArgs);
BENCHMARK(BM_QueryBatch)->Apply(queryArgs);

// The roofline of the kernel sum: how many 16-float vector operations this core retires per ns
// when, as in the sum, subtractions and multiply-adds alternate on independent chains (six of
// each, enough to hide their latency). Counter `vector_ops`, per second (8.3G/s = 8.3 per ns);
// docs/performance.md divides a kernel sum's operation count by it.
void BM_KernelPeak(benchmark::State& state) {
  using Lanes = Eigen::Array<float, 16, 1>;
  constexpr int kChains = 6;
  constexpr int kSteps = 1000;
  std::array<Lanes, kChains> products, differences;
  for (int k = 0; k < kChains; ++k) {
    products[k] = Lanes::Constant(1.0f + 1e-3f * static_cast<float>(k));
    differences[k] = Lanes::Constant(2.0f + 1e-3f * static_cast<float>(k));
  }
  const float a = 0.999f, b = 1e-6f;
  for (auto _ : state) {
    for (int i = 0; i < kSteps; ++i) {
      for (int k = 0; k < kChains; ++k) {
        products[k] = products[k] * a + b;
        differences[k] = differences[k] - b;
      }
    }
    benchmark::DoNotOptimize(products);
    benchmark::DoNotOptimize(differences);
  }
  state.counters["vector_ops"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kSteps * 2 * kChains, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_KernelPeak);

}  // namespace
}  // namespace fastron
