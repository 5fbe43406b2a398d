#pragma once
// A table of text cells written as CSV (results.csv), and the Markdown rows made from it.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace fastron::experiments {

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

/// Formats a number for a CSV cell (full precision, "nan" for NaN).
std::string cell(double value);

}  // namespace fastron::experiments
