#include "fastron/experiments/table.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "fastron/experiments/statistics.h"

namespace fastron::experiments {

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

std::string methodRow(const Table& r, const std::string& method, const Table::Filter& where,
                      const std::string& timeColumn, const std::array<std::string, 3>& paper) {
  auto stat = [&](const std::string& column) { return summarize(r.numbers(column, where)); };
  const Summary support = stat("support"), time = stat(timeColumn);
  return "| " + method + " | " + (support.count ? meanStd(support, 1) : "—") + " | " +
         durationMeanStd(stat("query_s")) + " | " + (time.count ? durationMeanStd(time) : "—") +
         " | " + meanStd(stat("accuracy"), 3) + " | " + meanStd(stat("tpr"), 3) + " | " +
         meanStd(stat("tnr"), 3) + " | " + paper[0] + " | " + paper[1] + " | " + paper[2] + " |\n";
}

}  // namespace fastron::experiments
