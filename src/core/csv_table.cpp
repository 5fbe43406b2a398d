#include "fastron/core/csv_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

#include "fastron/core/error.h"

namespace fastron {

std::string_view trimBlanks(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> splitCsvFields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trimBlanks(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

namespace {

/// The whole field as a number (a leading '+' allowed), or nothing.
std::optional<double> parseNumber(std::string_view field) {
  if (field.size() > 1 && field.front() == '+') field.remove_prefix(1);
  double value = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (error != std::errc() || end != field.data() + field.size() || field.empty()) return {};
  return value;
}

}  // namespace

CsvTable parseCsvTable(std::string_view text, const std::string& source) {
  CsvTable table;
  bool first = true;
  std::size_t lineNo = 0;
  // Line by line over the text itself, without copying it.
  for (std::size_t begin = 0; begin < text.size();) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    const std::string_view line = trimBlanks(text.substr(begin, end - begin));
    begin = end + 1;
    ++lineNo;
    if (line.empty()) continue;
    const std::vector<std::string_view> fields = splitCsvFields(line);
    const std::string where = source + ":" + std::to_string(lineNo);
    if (first) {
      first = false;
      table.firstLine = lineNo;
      table.columns = fields.size();
      // A header row is one without a single number in it.
      if (std::none_of(fields.begin(), fields.end(),
                       [](std::string_view field) { return parseNumber(field).has_value(); })) {
        table.header.assign(fields.begin(), fields.end());
        continue;
      }
    }
    if (fields.size() != table.columns) {
      throw FileError(where + ": " + std::to_string(fields.size()) + " columns, expected " +
                      std::to_string(table.columns));
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const std::string at = where + ": column " + std::to_string(c + 1);
      const auto value = parseNumber(fields[c]);
      if (!value) throw FileError(at + ": '" + std::string(fields[c]) + "' is not a number");
      if (!std::isfinite(*value))
        throw FileError(at + ": value is not finite (" + std::string(fields[c]) + ")");
      table.values.push_back(*value);
    }
    table.lineNumbers.push_back(lineNo);
  }
  return table;
}

}  // namespace fastron
