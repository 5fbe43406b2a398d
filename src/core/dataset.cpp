#include "fastron/core/dataset.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "fastron/core/csv_table.h"
#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "fastron/core/npy.h"

namespace fastron {
namespace {

std::int8_t toLabel(double value, const std::string& where) {
  if (value == 1.0) return 1;
  if (value == -1.0) return -1;
  throw FileError(where + ": label must be +1 or -1, got " + std::to_string(value));
}

Dataset fromRows(const std::vector<double>& values, std::size_t columns, Labels labels) {
  Dataset data;
  const auto n = static_cast<Eigen::Index>(labels.size());
  const auto d = static_cast<Eigen::Index>(columns - 1);
  data.points.resize(n, d);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < d; ++j) {
      data.points(i, j) =
          values[static_cast<std::size_t>(i) * (columns - 1) + static_cast<std::size_t>(j)];
    }
  }
  data.labels = std::move(labels);
  return data;
}

}  // namespace

Dataset parseCsv(std::string_view csv, const std::string& source) {
  const CsvTable table = parseCsvTable(csv, source);
  if (table.columns == 1) {
    throw FileError(source + ":" + std::to_string(table.firstLine) +
                    ": need at least one configuration column and a label column, found 1 column");
  }
  if (table.rows() == 0) throw FileError(source + ": no data rows");
  Dataset data;
  const std::size_t dim = table.columns - 1;
  data.points.resize(static_cast<Eigen::Index>(table.rows()), static_cast<Eigen::Index>(dim));
  for (std::size_t i = 0; i < table.rows(); ++i) {
    for (std::size_t j = 0; j < dim; ++j) {
      data.points(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = table.at(i, j);
    }
    data.labels.push_back(
        toLabel(table.at(i, dim), source + ":" + std::to_string(table.lineNumbers[i]) +
                                      ": column " + std::to_string(table.columns)));
  }
  if (!table.header.empty()) data.columnNames.assign(table.header.begin(), table.header.end() - 1);
  return data;
}

Dataset parseNpy(std::string_view bytes, const std::string& source) {
  const std::string& file = source;
  const NpyMatrix array(bytes, file);
  const std::size_t rows = array.rows(), columns = array.columns();
  if (columns < 2 || rows == 0) {
    throw FileError(file + ": expected a 2-D array with at least 2 columns and 1 row, got shape (" +
                    std::to_string(rows) + ", " + std::to_string(columns) + ")");
  }
  std::vector<double> values;
  values.reserve(rows * (columns - 1));
  Labels labels;
  labels.reserve(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns; ++c) {
      const double v = array.at(r, c);
      const std::string where =
          file + ": row " + std::to_string(r) + ", column " + std::to_string(c);
      if (!std::isfinite(v)) throw FileError(where + ": value is not finite");
      if (c + 1 < columns)
        values.push_back(v);
      else
        labels.push_back(toLabel(v, where));
    }
  }
  return fromRows(values, columns, std::move(labels));
}

Dataset readCsv(const std::filesystem::path& path) {
  return parseCsv(readFile(path, "dataset file"), path.string());
}

Dataset readNpy(const std::filesystem::path& path) {
  return parseNpy(readFile(path, "dataset file"), path.string());
}

Dataset rowsOf(const Dataset& data, const std::vector<Eigen::Index>& index) {
  Dataset out;
  out.points = data.points(index, Eigen::all);
  out.labels.reserve(index.size());
  for (const Eigen::Index i : index) out.labels.push_back(data.labels[static_cast<std::size_t>(i)]);
  out.columnNames = data.columnNames;
  return out;
}

void append(Dataset& data, const Dataset& rows) {
  if (rows.size() == 0) return;
  if (data.size() == 0) {
    data.points = rows.points;
    data.labels = rows.labels;
    return;
  }
  if (rows.dim() != data.dim()) {
    throw InvalidArgument("cannot append rows of " + std::to_string(rows.dim()) +
                          " columns to a dataset of " + std::to_string(data.dim()));
  }
  data.points.conservativeResize(data.points.rows() + rows.points.rows(), Eigen::NoChange);
  data.points.bottomRows(rows.points.rows()) = rows.points;
  data.labels.insert(data.labels.end(), rows.labels.begin(), rows.labels.end());
}

DatasetSplit splitHoldout(const Dataset& data, double heldOut, std::uint64_t seed) {
  if (!(heldOut >= 0 && heldOut < 1))
    throw InvalidArgument("the held-out share must be in [0, 1), got " + std::to_string(heldOut));
  std::vector<Eigen::Index> order(data.size());
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  const auto held = static_cast<std::size_t>(heldOut * static_cast<double>(data.size()));
  if (held > 0) {
    Rng rng(seed);
    std::shuffle(order.begin(), order.end(), rng);
  }
  const auto middle = order.begin() + static_cast<std::ptrdiff_t>(held);
  return {rowsOf(data, {middle, order.end()}), rowsOf(data, {order.begin(), middle})};
}

Dataset readDataset(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".npy") return readNpy(path);
  if (ext == ".csv" || ext == ".txt") return readCsv(path);
  throw FileError(path.string() + ": unknown dataset format '" + ext + "' (expected .csv or .npy)");
}

void writeDataset(const Dataset& data, const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".npy") return writeNpy(data, path);
  if (ext == ".csv" || ext == ".txt") return writeCsv(data, path);
  throw FileError(path.string() + ": unknown dataset format '" + ext + "' (expected .csv or .npy)");
}

void writeCsv(const Dataset& data, const std::filesystem::path& path) {
  std::ostringstream out;
  if (!data.columnNames.empty()) {
    for (const auto& name : data.columnNames) out << name << ',';
    out << "label\n";
  }
  out.precision(17);
  for (Eigen::Index i = 0; i < data.points.rows(); ++i) {
    for (Eigen::Index j = 0; j < data.points.cols(); ++j) out << data.points(i, j) << ',';
    out << static_cast<int>(data.labels[static_cast<std::size_t>(i)]) << '\n';
  }
  writeFileAtomically(path, out.view(), "dataset file");
}

void writeNpy(const Dataset& data, const std::filesystem::path& path) {
  const std::size_t rows = data.size(), columns = data.dim() + 1;
  std::vector<double> values;
  values.reserve(rows * columns);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c + 1 < columns; ++c)
      values.push_back(data.points(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)));
    values.push_back(data.labels[r]);
  }
  writeFileAtomically(path, npyBytes(values.data(), rows, columns), "dataset file");
}

}  // namespace fastron
