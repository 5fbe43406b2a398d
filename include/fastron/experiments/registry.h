#pragma once
// Every experiment of `fastron bench` (docs/experiments.md) in one list: its name, what it
// measures, the settings it reads, its defaults (full and --quick), and how to run it.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fastron/core/feature_map.h"
#include "fastron/experiments/progress.h"
#include "fastron/experiments/table.h"
#include "fastron/planning/planner.h"

namespace fastron::experiments {

/// What a user can set for any experiment; 0 (or -1, or empty) keeps the experiment's default,
/// which --quick makes small. Each experiment reads the settings it lists in Experiment::settings.
struct ExperimentSettings {
  std::size_t trials = 0;  ///< random environments, planning queries; surgical: ticks
  std::uint64_t seed = 1;
  bool quick = false;
  FeatureKind features = FeatureKind::Kinematic;
  double timeLimit = 0, resolution = 0;              ///< planning experiments
  double range = 0;                                  ///< motion-bench
  std::optional<std::size_t> rangeStage;             ///< motion-bench
  double modelResolution = 0;                        ///< planning experiments
  double simplifyTime = -1;                          ///< planning experiments; < 0: default
  std::optional<PathSimplification> simplification;  ///< planning experiments; none: Full
  double gamma = 0, beta = 0, variance = 0;          ///< changing; gamma, beta also motion-bench
  std::size_t activeSamples = 0;                     ///< changing
  bool warmStart = false;                            ///< changing
  std::size_t pruneSamples = 0;                      ///< changing
  double mergeRadius = 0;                            ///< changing
  std::optional<std::uint32_t> kernelBlock;          ///< changing
  std::optional<double> wholeShare;                  ///< changing
  // motion-bench
  std::filesystem::path problems;
  std::string robot = "panda";
  std::vector<std::filesystem::path> packagePaths;
  std::filesystem::path srdf;
  bool selfCollision = false;
  bool denseChecks = false;
  bool selfPairTables = true;  ///< motion-bench: MotionBenchOptions::selfPairTables
  std::size_t queriesPerScene = 1;
  bool selfModel = false;
  bool learnFromVerification = false;
  bool gradientRepair = false;  ///< motion-bench, optimize: VerifyRepairOptions::gradientRepair
  std::optional<std::size_t> samples, updates;  ///< motion-bench: each scene's training
  /// Where a long batch run (motion-bench) writes its rows so far, in results.csv's format, so
  /// that an interrupted run leaves them (empty: nowhere).
  std::filesystem::path resultsFile;
};

/// What an experiment produced: the rows of results.csv, further tables by file name (e.g.
/// "grid.csv"), and the Markdown report.
struct ExperimentOutput {
  Table results;
  std::vector<std::pair<std::string, Table>> tables;
  std::string report;
};

struct Experiment {
  std::string name;
  std::string description;
  /// The settings it reads beyond trials, seed and quick, by their option names ("time-limit",
  /// "gamma", ...): `fastron bench` refuses the others.
  std::vector<std::string> settings;
  std::function<ExperimentOutput(const ExperimentSettings&, const Progress&)> run;
};

/// Every experiment, in the order of the paper.
const std::vector<Experiment>& experimentRegistry();
/// The experiment named `name`; throws InvalidArgument naming the known ones.
const Experiment& findExperiment(std::string_view name);

}  // namespace fastron::experiments
