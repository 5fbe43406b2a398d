#pragma once
// A CSV file of numbers, with an optional header row: what a labelled dataset and a path file
// are made of. Every problem is reported with the file, line and column.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

struct CsvTable {
  std::vector<std::string> header;       ///< the header row's fields; empty without one
  std::size_t columns = 0;               ///< fields per row
  std::vector<double> values;            ///< row by row, `columns` per row
  std::vector<std::size_t> lineNumbers;  ///< the file's line (from 1) of each row
  std::size_t firstLine = 0;             ///< the line of the header or first row; 0: none

  std::size_t rows() const { return lineNumbers.size(); }
  double at(std::size_t row, std::size_t column) const { return values[row * columns + column]; }
};

/// `text` without the blanks (spaces, tabs, a carriage return) around it.
std::string_view trimBlanks(std::string_view text);
/// `line` cut at its commas, each field without the blanks around it.
std::vector<std::string_view> splitCsvFields(std::string_view line);

/// Parses `text`, naming `source` in errors. Blank lines are skipped; the first other line is a
/// header when none of its fields is a number. Throws FileError "<source>:<line>: ..." on a row of
/// another number of fields than the first, and "<source>:<line>: column <c>: ..." on a field
/// that is not a number or not finite; a file without rows is accepted (rows() == 0).
CsvTable parseCsvTable(std::string_view text, const std::string& source);

}  // namespace fastron
