#include "fastron/experiments/common.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "fastron/core/error.h"
#include "fastron/proxy/parallel_chunks.h"

namespace fastron::experiments {

Summary summarize(const std::vector<double>& values) {
  Summary s;
  double sum = 0, squares = 0;
  for (const double v : values) {
    if (std::isnan(v)) continue;
    sum += v;
    ++s.count;
  }
  if (s.count == 0) return {std::nan(""), std::nan(""), 0, std::nan("")};
  s.mean = sum / static_cast<double>(s.count);
  for (const double v : values) {
    if (!std::isnan(v)) squares += (v - s.mean) * (v - s.mean);
  }
  s.stddev = s.count > 1 ? std::sqrt(squares / static_cast<double>(s.count - 1)) : 0.0;
  std::vector<double> sorted;
  sorted.reserve(s.count);
  for (const double v : values) {
    if (!std::isnan(v)) sorted.push_back(v);
  }
  std::sort(sorted.begin(), sorted.end());
  const std::size_t middle = sorted.size() / 2;
  s.median = sorted.size() % 2 ? sorted[middle] : 0.5 * (sorted[middle - 1] + sorted[middle]);
  return s;
}

std::string meanStd(const Summary& s, int digits) {
  if (s.count == 0) return "n/a";
  char buffer[64];
  if (s.count == 1) {  // one value has no spread to report
    std::snprintf(buffer, sizeof buffer, "%.*f", digits, s.mean);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.*f ± %.*f", digits, s.mean, digits, s.stddev);
  }
  return buffer;
}

namespace {

struct Unit {
  double scale;
  const char* name;
  int digits;  // decimals: 2 below 10 units, 1 above
};

Unit unitFor(double seconds) {
  const auto unit = [&](double scale, const char* name) {
    return Unit{scale, name, seconds * scale < 10 ? 2 : 1};
  };
  return seconds < 1e-6   ? unit(1e9, "ns")
         : seconds < 1e-3 ? unit(1e6, "µs")
         : seconds < 1    ? unit(1e3, "ms")
                          : unit(1, "s");
}

}  // namespace

std::string durationMeanStd(const Summary& seconds) {
  if (seconds.count == 0) return "n/a";
  const Unit unit = unitFor(seconds.mean);
  return meanStd({seconds.mean * unit.scale, seconds.stddev * unit.scale, seconds.count},
                 unit.digits) +
         " " + unit.name;
}

std::string durationText(double seconds) {
  const Unit unit = unitFor(seconds);
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f %s", unit.digits, seconds * unit.scale, unit.name);
  return buffer;
}

void Table::add(std::vector<std::string> row) {
  if (row.size() != columns.size())
    throw InvalidArgument("table row has the wrong number of cells");
  rows.push_back(std::move(row));
}

std::size_t Table::index(const std::string& column) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == column) return i;
  }
  throw InvalidArgument("table has no column '" + column + "'");
}

namespace {

bool matches(const Table& t, const std::vector<std::string>& row, const Table::Filter& where) {
  for (const auto& [column, value] : where) {
    if (row[t.index(column)] != value) return false;
  }
  return true;
}

}  // namespace

std::vector<double> Table::numbers(const std::string& column, const Filter& where) const {
  const std::size_t c = index(column);
  std::vector<double> values;
  for (const auto& row : rows) {
    if (matches(*this, row, where))
      values.push_back(row[c] == "nan" ? std::nan("") : std::stod(row[c]));
  }
  return values;
}

std::vector<std::string> Table::distinct(const std::string& column, const Filter& where) const {
  const std::size_t c = index(column);
  std::vector<std::string> values;
  for (const auto& row : rows) {
    if (matches(*this, row, where) &&
        std::find(values.begin(), values.end(), row[c]) == values.end())
      values.push_back(row[c]);
  }
  return values;
}

namespace {

// RFC 4180: a cell with a comma, quote or line break is quoted, its quotes doubled.
std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

void Table::writeCsv(const std::filesystem::path& path) const {
  std::ofstream out(path);
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << csvField(columns[i]);
  out << '\n';
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << csvField(row[i]);
    out << '\n';
  }
  out.close();
  if (!out) throw FileError(path.string() + ": cannot write");
}

std::string cell(double value) {
  if (std::isnan(value)) return "nan";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  return buffer;
}

double meanSecondsPerCall(const Configurations& q, const std::function<bool(const double*)>& fn,
                          double minSeconds) {
  using Clock = std::chrono::steady_clock;
  std::size_t calls = 0;
  [[maybe_unused]] volatile bool sink = false;  // keeps the calls from being optimised away
  const auto start = Clock::now();
  do {
    for (Eigen::Index i = 0; i < q.rows(); ++i) sink = fn(q.row(i).data());
    calls += static_cast<std::size_t>(q.rows());
  } while (std::chrono::duration<double>(Clock::now() - start).count() < minSeconds &&
           q.rows() > 0);
  return calls == 0 ? std::nan("")
                    : std::chrono::duration<double>(Clock::now() - start).count() /
                          static_cast<double>(calls);
}

double meanSecondsPerCheck(const Configurations& q, const CollisionChecker& checker,
                           double minSeconds) {
  const auto d = static_cast<std::size_t>(q.cols());
  return meanSecondsPerCall(
      q,
      [&](const double* x) {
        return checker.inCollision({x, d});
      },
      minSeconds);
}

std::vector<double> clearances(const SceneChecker& exact, const Configurations& q) {
  std::vector<double> distance(static_cast<std::size_t>(q.rows()));
  forEachChunk(distance.size(), 8, 0, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      distance[i] = exact.distance({q.row(static_cast<Eigen::Index>(i)).data(), exact.dof()});
    }
  });
  return distance;
}

std::string methodRow(const Table& r, const std::string& method, const Table::Filter& where,
                      const std::string& timeColumn, const std::array<std::string, 3>& paper) {
  auto stat = [&](const std::string& column) { return summarize(r.numbers(column, where)); };
  const Summary support = stat("support"), time = stat(timeColumn);
  return "| " + method + " | " + (support.count ? meanStd(support, 1) : "—") + " | " +
         durationMeanStd(stat("query_s")) + " | " + (time.count ? durationMeanStd(time) : "—") +
         " | " + meanStd(stat("accuracy"), 3) + " | " + meanStd(stat("tpr"), 3) + " | " +
         meanStd(stat("tnr"), 3) + " | " + paper[0] + " | " + paper[1] + " | " + paper[2] + " |\n";
}

Scene randomCubes(std::size_t maxCubes, double minSide, double maxSide, double reach, Rng& rng) {
  std::uniform_int_distribution<std::size_t> count(1, maxCubes);
  std::uniform_real_distribution<double> side(minSide, maxSide), unit(-1.0, 1.0),
      yaw(-3.14159, 3.14159);
  Scene scene;
  const std::size_t n = count(rng);
  while (scene.size() < n) {
    const double s = side(rng);
    const Eigen::Vector3d c(reach * unit(rng), reach * unit(rng), reach * std::abs(unit(rng)));
    // In reach, and clear of the base: a cube holding the base would fill the whole C-space.
    if (c.norm() > reach || c.norm() < s * 0.87 + 0.08) continue;
    scene.add({"cube" + std::to_string(scene.size() + 1), Box{Eigen::Vector3d::Constant(s)},
               makePose(c, {0, 0, yaw(rng)}), std::nullopt});
  }
  return scene;
}

std::string featureSentence(FeatureKind kind) {
  return kind == FeatureKind::Kinematic
             ? "Fastron learns on task-space features: the world positions of the robot's "
               "automatic control points (docs/algorithms.md)."
             : "Fastron learns on joint values scaled to [-1, 1] (the paper's input).";
}

std::string simplificationSentence(double simplifyTime, PathSimplification simplification) {
  if (simplifyTime <= 0) return "Paths are not simplified (the paper's setting).";
  std::ostringstream s;
  s << "Every method's path is simplified with OMPL's PathSimplifier for up to " << simplifyTime
    << " s, on the checker that planned it (FCL pays for its simplification in exact checks; "
       "Fastron's is checked on the model and then verified), "
    << (simplification == PathSimplification::Full
            ? "as MoveIt does by default."
            : "by shortcutting and vertex reduction alone (no B-spline smoothing).");
  return s.str();
}

}  // namespace fastron::experiments
