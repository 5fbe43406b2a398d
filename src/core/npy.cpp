#include "fastron/core/npy.h"

#include <charconv>
#include <cstdint>
#include <cstring>
#include <vector>

#include "fastron/core/csv_table.h"
#include "fastron/core/error.h"

namespace fastron {
namespace {

/// The header's text and where the data start.
struct NpyHeader {
  std::string text;
  std::size_t dataStart = 0;
};

NpyHeader npyHeader(std::string_view bytes, const std::string& file) {
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
  return {std::string(bytes.substr(headerStart, headerLength)), headerStart + headerLength};
}

}  // namespace

NpyMatrix::NpyMatrix(std::string_view bytes, const std::string& source) {
  const std::string& file = source;
  const NpyHeader header = npyHeader(bytes, file);
  auto valueOf = [&](const std::string& key) {
    const std::size_t k = header.text.find("'" + key + "'");
    const std::size_t colon = k == std::string::npos ? k : header.text.find(':', k);
    if (colon == std::string::npos)
      throw FileError(file + ": .npy header has no '" + key + "' field");
    return trimBlanks(std::string_view(header.text).substr(colon + 1));
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
  fortran_ = valueOf("fortran_order").starts_with("True");
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
  if (shape.size() != 2) {
    throw FileError(file + ": expected a 2-D array, got shape (" + std::string(shapeText) + ")");
  }
  if (descr == "<f8" || descr == "<i8") {
    itemSize_ = 8;
  } else if (descr == "<f4" || descr == "<i4") {
    itemSize_ = 4;
  } else {
    throw FileError(file + ": unsupported .npy dtype '" + std::string(descr) +
                    "' (use <f8, <f4, <i8 or <i4)");
  }
  type_ = descr[1];
  rows_ = shape[0];
  columns_ = shape[1];
  const std::size_t available = (bytes.size() - header.dataStart) / itemSize_;  // whole elements
  if (rows_ > 0 && columns_ > 0 && (columns_ > available || rows_ > available / columns_)) {
    throw FileError(file + ": truncated .npy data (" +
                    std::to_string(bytes.size() - header.dataStart) + " bytes for shape (" +
                    std::to_string(rows_) + ", " + std::to_string(columns_) + "))");
  }
  data_ = bytes.substr(header.dataStart);
}

double NpyMatrix::at(std::size_t r, std::size_t c) const {
  const std::size_t index = fortran_ ? c * rows_ + r : r * columns_ + c;
  const char* p = data_.data() + index * itemSize_;
  if (type_ == 'f' && itemSize_ == 8) {
    double v;
    std::memcpy(&v, p, 8);
    return v;
  }
  if (type_ == 'f') {
    float v;
    std::memcpy(&v, p, 4);
    return v;
  }
  if (itemSize_ == 8) {
    std::int64_t v;
    std::memcpy(&v, p, 8);
    return static_cast<double>(v);
  }
  std::int32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

std::string npyBytes(const double* values, std::size_t rows, std::size_t columns) {
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
  bytes.append(reinterpret_cast<const char*>(values), rows * columns * sizeof(double));
  return bytes;
}

}  // namespace fastron
