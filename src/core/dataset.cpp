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

namespace {

/// What a .npy header says of the array after it.
struct NpyLayout {
  std::size_t dataStart = 0;  ///< offset of the first element
  std::string descr;          ///< "<f8", "<f4", "<i8" or "<i4"
  std::size_t itemSize = 0;
  bool fortran = false;
  std::size_t rows = 0, columns = 0;
};

/// The layout of a .npy file of a 2-D array of at least 2 columns, whose data are all present;
/// throws FileError naming `file` and what is wrong.
NpyLayout parseNpyHeader(std::string_view bytes, const std::string& file) {
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) {
    throw FileError(file + ": not a .npy file (bad magic bytes)");
  }
  const auto major = static_cast<unsigned char>(bytes[6]);
  std::size_t headerLength = 0, headerStart = 0;
  if (major == 1) {
    headerLength = static_cast<unsigned char>(bytes[8]) |
                   static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8;
    headerStart = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) throw FileError(file + ": truncated .npy header");
    for (int b = 3; b >= 0; --b)
      headerLength = headerLength << 8 | static_cast<unsigned char>(bytes[8 + b]);
    headerStart = 12;
  } else {
    throw FileError(file + ": unsupported .npy version " + std::to_string(major));
  }
  if (bytes.size() < headerStart + headerLength) throw FileError(file + ": truncated .npy header");
  const std::string header(bytes.substr(headerStart, headerLength));

  auto valueOf = [&](const std::string& key) {
    const std::size_t k = header.find("'" + key + "'");
    const std::size_t colon = k == std::string::npos ? k : header.find(':', k);
    if (colon == std::string::npos)
      throw FileError(file + ": .npy header has no '" + key + "' field");
    return trimBlanks(std::string_view(header).substr(colon + 1));
  };
  auto enclosed = [&](std::string_view text, char open, char close, const char* key) {
    const std::size_t end =
        text.empty() || text.front() != open ? std::string_view::npos : text.find(close, 1);
    if (end == std::string_view::npos)
      throw FileError(file + ": bad .npy header field '" + key + "'");
    return text.substr(1, end - 1);
  };
  const std::string_view descrText = valueOf("descr");
  const char quote = descrText.starts_with('"') ? '"' : '\'';
  const std::string_view descr = enclosed(descrText, quote, quote, "descr");
  NpyLayout layout;
  layout.fortran = valueOf("fortran_order").starts_with("True");
  const std::string_view shapeText = enclosed(valueOf("shape"), '(', ')', "shape");
  std::vector<std::size_t> shape;
  for (const auto field : splitCsvFields(shapeText)) {
    if (field.empty()) continue;
    std::size_t v = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (error != std::errc() || end != field.data() + field.size()) {
      throw FileError(file + ": bad .npy shape '" + std::string(shapeText) + "'");
    }
    shape.push_back(v);
  }
  if (shape.size() != 2 || shape[1] < 2 || shape[0] == 0) {
    throw FileError(file + ": expected a 2-D array with at least 2 columns and 1 row, got shape (" +
                    std::string(shapeText) + ")");
  }

  std::size_t& itemSize = layout.itemSize;
  if (descr == "<f8" || descr == "<i8")
    itemSize = 8;
  else if (descr == "<f4" || descr == "<i4")
    itemSize = 4;
  else
    throw FileError(file + ": unsupported .npy dtype '" + std::string(descr) +
                    "' (use <f8, <f4, <i8 or <i4)");

  const std::size_t rows = shape[0], columns = shape[1];
  layout.rows = rows;
  layout.columns = columns;
  layout.descr = std::string(descr);
  const std::size_t dataStart = headerStart + headerLength;
  const std::size_t available = (bytes.size() - dataStart) / itemSize;  // whole elements present
  if (columns > available || rows > available / columns) {
    throw FileError(file + ": truncated .npy data (" + std::to_string(bytes.size() - dataStart) +
                    " bytes for shape (" + std::to_string(rows) + ", " + std::to_string(columns) +
                    "))");
  }
  layout.dataStart = dataStart;
  return layout;
}

/// Element (r, c) of the array `layout` describes, as a double.
double npyElement(std::string_view bytes, const NpyLayout& layout, std::size_t r, std::size_t c) {
  const std::size_t index = layout.fortran ? c * layout.rows + r : r * layout.columns + c;
  const char* p = bytes.data() + layout.dataStart + index * layout.itemSize;
  if (layout.descr == "<f8") {
    double v;
    std::memcpy(&v, p, 8);
    return v;
  }
  if (layout.descr == "<f4") {
    float v;
    std::memcpy(&v, p, 4);
    return v;
  }
  if (layout.descr == "<i8") {
    std::int64_t v;
    std::memcpy(&v, p, 8);
    return static_cast<double>(v);
  }
  std::int32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

}  // namespace

Dataset parseNpy(std::string_view bytes, const std::string& source) {
  const std::string& file = source;
  const NpyLayout layout = parseNpyHeader(bytes, file);
  const std::size_t rows = layout.rows, columns = layout.columns;
  std::vector<double> values;
  values.reserve(rows * (columns - 1));
  Labels labels;
  labels.reserve(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns; ++c) {
      const double v = npyElement(bytes, layout, r, c);
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
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" +
                       std::to_string(rows) + ", " + std::to_string(columns) + "), }";
  // The header, with the 10 preamble bytes, is padded with spaces to a multiple of 64 and ends
  // with a newline (NumPy format version 1.0).
  header.append(63 - (10 + header.size()) % 64, ' ');
  header.push_back('\n');
  std::string bytes = "\x93NUMPY";
  bytes.push_back('\x01');
  bytes.push_back('\x00');
  bytes.push_back(static_cast<char>(header.size() & 0xff));
  bytes.push_back(static_cast<char>(header.size() >> 8));
  bytes += header;
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns; ++c) {
      const double v = c + 1 < columns
                           ? data.points(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c))
                           : data.labels[r];
      bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
  }
  writeFileAtomically(path, bytes, "dataset file");
}

}  // namespace fastron
