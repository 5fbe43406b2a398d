#pragma once
// What every experiment shares: progress reports, statistics, timing, tables, random scenes.

#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/collision_checker.h"
#include "fastron/core/feature_map.h"
#include "fastron/core/types.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/scene.h"
#include "fastron/geometry/scene_checker.h"
#include "fastron/planning/planner.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron::experiments {

/// Called with a line of progress; the command prints it, the library never does.
using Progress = std::function<void(std::string_view)>;

struct Summary {
  double mean = 0, stddev = 0;
  std::size_t count = 0;
  double median = 0;
};
/// Mean, sample standard deviation and median, ignoring NaN values.
Summary summarize(const std::vector<double>& values);
/// "12.3 ± 4.5" with `digits` decimals ("12.3" for a single value).
std::string meanStd(const Summary& s, int digits);
/// A duration in seconds as "mean ± std unit" with a unit chosen for the mean (ns, µs, ms, s).
std::string durationMeanStd(const Summary& seconds);
/// One duration in seconds with the unit durationMeanStd would choose, e.g. "2.14 µs".
std::string durationText(double seconds);

/// A table of text cells with a header: written as CSV, read back by the plot scripts.
struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  void add(std::vector<std::string> row);
  using Filter = std::vector<std::pair<std::string, std::string>>;
  /// Values of one column, as numbers, of the rows whose cells equal every (column, value) of
  /// `where`.
  std::vector<double> numbers(const std::string& column, const Filter& where = {}) const;
  /// The distinct values of a column, in order of appearance.
  std::vector<std::string> distinct(const std::string& column, const Filter& where = {}) const;
  std::size_t index(const std::string& column) const;
  void writeCsv(const std::filesystem::path& path) const;
};

/// A row of the paper's method tables in Markdown: method, |S|, query time, `timeColumn` (training
/// or update time), accuracy, TPR, TNR as mean ± std over the rows matching `where`, then the
/// paper's |S|, query time and training time (empty cells where the paper has none).
std::string methodRow(const Table& results, const std::string& method, const Table::Filter& where,
                      const std::string& timeColumn, const std::array<std::string, 3>& paper);

/// A sentence for reports saying what Fastron learned on.
std::string featureSentence(FeatureKind kind);
/// A sentence for reports saying whether and how long paths were simplified.
std::string simplificationSentence(double simplifyTime, PathSimplification simplification);

/// Formats a number for a CSV cell (full precision, "nan" for NaN).
std::string cell(double value);

/// Mean seconds per exact check of each row of q (a checker's inCollision).
double meanSecondsPerCheck(const Configurations& q, const CollisionChecker& checker,
                           double minSeconds = 0.05);

/// Each row's distance to the nearest obstacle under `exact` (0 for one in collision), on every
/// core: between meshes a distance takes milliseconds (about 3 ms on the mesh Panda).
std::vector<double> clearances(const SceneChecker& exact, const Configurations& q);

/// Mean seconds per call of `fn` on each row of q, over at least `minSeconds` (whole passes).
double meanSecondsPerCall(const Configurations& q, const std::function<bool(const double*)>& fn,
                          double minSeconds = 0.05);

/// Up to `maxCubes` cubes (at least one) of random size in [minSide, maxSide], centred in the
/// upper half of the ball of radius `reach` around the robot's base, and clear of the base.
Scene randomCubes(std::size_t maxCubes, double minSide, double maxSide, double reach, Rng& rng);

}  // namespace fastron::experiments
