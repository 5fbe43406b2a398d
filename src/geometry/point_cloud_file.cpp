#include "fastron/geometry/point_cloud_file.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"
#include "fastron/core/npy.h"
#include "octomap_file.h"

namespace fastron {
namespace {

std::string count(std::size_t n) {
  return std::to_string(n);
}

void requireFinite(const Eigen::Vector3d& p, std::size_t index, const std::string& where) {
  if (!p.allFinite()) throw FileError(where + ": point " + count(index) + " is not finite");
}

void requireFewEnough(std::size_t n, std::size_t maxPoints, const std::string& where) {
  if (n > maxPoints)
    throw FileError(where + ": " + count(n) + " points declared, more than the " +
                    count(maxPoints) + " a cloud may hold");
}

CloudPoints npyCloud(std::string_view bytes, const std::string& source, std::size_t maxPoints) {
  const NpyMatrix array(bytes, source);
  if (array.columns() != 3)
    throw FileError(source + ": expected an (n, 3) array of points, got shape (" +
                    count(array.rows()) + ", " + count(array.columns()) + ")");
  requireFewEnough(array.rows(), maxPoints, source);
  CloudPoints cloud;
  cloud.points.reserve(array.rows());
  for (std::size_t r = 0; r < array.rows(); ++r) {
    cloud.points.emplace_back(array.at(r, 0), array.at(r, 1), array.at(r, 2));
    requireFinite(cloud.points.back(), r, source);
  }
  return cloud;
}

/// The lines of a header, one at a time, with their numbers; the bytes after the last line read.
class HeaderLines {
 public:
  HeaderLines(std::string_view bytes, std::string source)
      : bytes_(bytes), source_(std::move(source)) {}
  /// The next line without its end of line; nullopt at the end of the bytes.
  std::optional<std::string_view> next() {
    if (position_ >= bytes_.size()) return std::nullopt;
    const std::size_t end = bytes_.find('\n', position_);
    std::string_view line = bytes_.substr(
        position_, end == std::string_view::npos ? std::string_view::npos : end - position_);
    position_ = end == std::string_view::npos ? bytes_.size() : end + 1;
    ++line_;
    if (line.ends_with('\r')) line.remove_suffix(1);
    return line;
  }
  std::string where() const { return source_ + ":" + count(line_); }
  [[noreturn]] void fail(const std::string& message) const {
    throw FileError(where() + ": " + message);
  }
  std::string_view rest() const { return bytes_.substr(position_); }

 private:
  std::string_view bytes_;
  std::string source_;
  std::size_t position_ = 0, line_ = 0;
};

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::optional<double> parseNumber(std::string_view word) {
  double v = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), v);
  if (error != std::errc() || end != word.data() + word.size()) {
    // from_chars refuses "nan" spelled as some writers do ("NaN"): a NaN all the same.
    if (word == "nan" || word == "NaN" || word == "-nan") return std::nan("");
    return std::nullopt;
  }
  return v;
}

std::size_t parseCount(std::string_view word, const HeaderLines& lines, const char* what) {
  std::size_t v = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), v);
  if (error != std::errc() || end != word.data() + word.size())
    lines.fail(std::string(what) + " '" + std::string(word) + "' is not a count");
  return v;
}

/// A binary scalar: its size and how it reads as a double.
struct ScalarType {
  char kind = 'f';  // 'f' float, 'i' signed, 'u' unsigned
  std::size_t size = 4;
};

/// The little-endian scalar of type T at p, as a double.
template <class T>
double scalarAt(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return static_cast<double>(v);
}

double readScalar(const char* p, ScalarType type) {
  switch (type.kind) {
    case 'f':
      return type.size == 8 ? scalarAt<double>(p) : scalarAt<float>(p);
    case 'i':
      return type.size == 1   ? scalarAt<std::int8_t>(p)
             : type.size == 2 ? scalarAt<std::int16_t>(p)
                              : scalarAt<std::int32_t>(p);
    default:
      return type.size == 1   ? scalarAt<std::uint8_t>(p)
             : type.size == 2 ? scalarAt<std::uint16_t>(p)
                              : scalarAt<std::uint32_t>(p);
  }
}

// ---- PLY ----

std::optional<ScalarType> plyType(std::string_view name) {
  if (name == "char" || name == "int8") return ScalarType{'i', 1};
  if (name == "uchar" || name == "uint8") return ScalarType{'u', 1};
  if (name == "short" || name == "int16") return ScalarType{'i', 2};
  if (name == "ushort" || name == "uint16") return ScalarType{'u', 2};
  if (name == "int" || name == "int32") return ScalarType{'i', 4};
  if (name == "uint" || name == "uint32") return ScalarType{'u', 4};
  if (name == "float" || name == "float32") return ScalarType{'f', 4};
  if (name == "double" || name == "float64") return ScalarType{'f', 8};
  return std::nullopt;
}

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<std::string> properties;
  std::vector<ScalarType> types;
  bool hasList = false;
  std::size_t stride = 0;  // bytes per instance without lists
};

struct PlyHeader {
  bool binary = false;
  std::vector<PlyElement> elements;
};

PlyHeader plyHeader(HeaderLines& lines) {
  const auto magic = lines.next();
  if (!magic || *magic != "ply") lines.fail("not a PLY file (it does not start with 'ply')");
  PlyHeader header;
  bool format = false;
  while (const auto line = lines.next()) {
    const auto w = words(*line);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") {
      if (!format) lines.fail("the PLY header has no 'format' line");
      return header;
    }
    if (w[0] == "format") {
      if (w.size() != 3) lines.fail("expected 'format <type> 1.0'");
      if (w[1] == "ascii") {
        header.binary = false;
      } else if (w[1] == "binary_little_endian") {
        header.binary = true;
      } else {
        lines.fail("PLY format '" + std::string(w[1]) +
                   "' is not supported (ascii, binary_little_endian)");
      }
      format = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) lines.fail("expected 'element <name> <count>'");
      PlyElement element;
      element.name = std::string(w[1]);
      element.count = parseCount(w[2], lines, "element count");
      header.elements.push_back(std::move(element));
    } else if (w[0] == "property") {
      if (header.elements.empty()) lines.fail("a property before any element");
      PlyElement& e = header.elements.back();
      if (w.size() == 5 && w[1] == "list") {
        e.hasList = true;
        e.properties.emplace_back(w[4]);
        e.types.push_back({});
        continue;
      }
      if (w.size() != 3) lines.fail("expected 'property <type> <name>'");
      const auto type = plyType(w[1]);
      if (!type) lines.fail("unknown PLY property type '" + std::string(w[1]) + "'");
      e.properties.emplace_back(w[2]);
      e.types.push_back(*type);
      e.stride += type->size;
    } else {
      lines.fail("unknown PLY header line '" + std::string(*line) + "'");
    }
  }
  lines.fail("the PLY header has no 'end_header' line");
}

std::size_t propertyIndex(const PlyElement& e, const char* name, const HeaderLines& lines) {
  for (std::size_t i = 0; i < e.properties.size(); ++i)
    if (e.properties[i] == name) return i;
  lines.fail("the vertex element has no '" + std::string(name) + "' property");
}

CloudPoints plyCloud(std::string_view bytes, const std::string& source, std::size_t maxPoints) {
  HeaderLines lines(bytes, source);
  const PlyHeader header = plyHeader(lines);
  std::size_t vertex = header.elements.size();
  for (std::size_t i = 0; i < header.elements.size() && vertex == header.elements.size(); ++i) {
    if (header.elements[i].name == "vertex") vertex = i;
  }
  if (vertex == header.elements.size())
    throw FileError(source + ": PLY file has no vertex element");
  const PlyElement& v = header.elements[vertex];
  if (v.hasList) throw FileError(source + ": the PLY vertex element has a list property");
  const std::size_t axes[3] = {propertyIndex(v, "x", lines), propertyIndex(v, "y", lines),
                               propertyIndex(v, "z", lines)};
  CloudPoints cloud;
  if (header.binary) {
    std::string_view data = lines.rest();
    for (std::size_t i = 0; i < vertex; ++i) {
      const PlyElement& e = header.elements[i];
      if (e.hasList)
        throw FileError(source + ": cannot skip PLY element '" + e.name +
                        "' (it has a list property) before the vertex element");
      if (e.count > 0 && e.stride > data.size() / e.count)
        throw FileError(source + ": truncated PLY data in element '" + e.name + "'");
      data.remove_prefix(e.count * e.stride);
    }
    if (v.count > 0 && v.stride > data.size() / v.count)
      throw FileError(source + ": truncated PLY data (" + count(data.size()) + " bytes for " +
                      count(v.count) + " vertices of " + count(v.stride) + " bytes)");
    requireFewEnough(v.count, maxPoints, source);
    std::size_t offsets[3];
    for (int a = 0; a < 3; ++a) {
      offsets[a] = 0;
      for (std::size_t k = 0; k < axes[a]; ++k) offsets[a] += v.types[k].size;
    }
    cloud.points.reserve(v.count);
    for (std::size_t i = 0; i < v.count; ++i) {
      const char* p = data.data() + i * v.stride;
      cloud.points.emplace_back(readScalar(p + offsets[0], v.types[axes[0]]),
                                readScalar(p + offsets[1], v.types[axes[1]]),
                                readScalar(p + offsets[2], v.types[axes[2]]));
      requireFinite(cloud.points.back(), i, source);
    }
    return cloud;
  }
  requireFewEnough(v.count, maxPoints, source);
  std::size_t skip = 0;
  for (std::size_t i = 0; i < vertex; ++i) skip += header.elements[i].count;
  for (std::size_t i = 0; i < skip; ++i) {
    if (!lines.next()) lines.fail("truncated PLY data before the vertex element");
  }
  cloud.points.reserve(std::min(v.count, bytes.size() / 6));  // "0 0 0\n" at least
  for (std::size_t i = 0; i < v.count; ++i) {
    const auto line = lines.next();
    if (!line)
      throw FileError(source + ": truncated PLY data: " + count(i) + " of " + count(v.count) +
                      " vertices");
    const auto w = words(*line);
    if (w.size() < v.properties.size())
      lines.fail("expected " + count(v.properties.size()) + " values, found " + count(w.size()));
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) {
      const auto value = parseNumber(w[axes[a]]);
      if (!value) lines.fail("'" + std::string(w[axes[a]]) + "' is not a number");
      p[a] = *value;
    }
    if (!p.allFinite()) lines.fail("point " + count(i) + " is not finite");
    cloud.points.push_back(p);
  }
  return cloud;
}

// ---- PCD ----

struct PcdField {
  std::string name;
  ScalarType type;
  std::size_t count = 1;
};

struct PcdHeader {
  std::vector<PcdField> fields;
  std::size_t width = 0, height = 1, points = 0;
  bool pointsGiven = false;
  std::string data;
};

void pcdFieldTypes(PcdHeader& h, const std::vector<std::string_view>& sizes,
                   const std::vector<std::string_view>& types, const HeaderLines& lines) {
  if (sizes.size() != h.fields.size() || types.size() != h.fields.size())
    lines.fail("FIELDS, SIZE and TYPE must have one entry per field");
  for (std::size_t i = 0; i < h.fields.size(); ++i) {
    const std::size_t size = parseCount(sizes[i], lines, "SIZE");
    const char kind = types[i] == "F" ? 'f' : types[i] == "I" ? 'i' : types[i] == "U" ? 'u' : '?';
    const bool valid = kind == 'f' ? (size == 4 || size == 8)
                                   : kind != '?' && (size == 1 || size == 2 || size == 4);
    if (!valid)
      lines.fail("field '" + h.fields[i].name + "': TYPE " + std::string(types[i]) + " SIZE " +
                 std::string(sizes[i]) + " is not supported");
    h.fields[i].type = {kind, size};
  }
}

PcdHeader pcdHeader(HeaderLines& lines) {
  PcdHeader h;
  std::vector<std::string_view> sizes, types;
  while (const auto line = lines.next()) {
    const auto w = words(*line);
    if (w.empty() || w[0].starts_with('#')) continue;
    const std::vector<std::string_view> values(w.begin() + 1, w.end());
    if (w[0] == "VERSION" || w[0] == "VIEWPOINT") continue;
    if (w[0] == "FIELDS") {
      for (const auto f : values) h.fields.push_back({std::string(f), {}, 1});
    } else if (w[0] == "SIZE") {
      sizes = values;
    } else if (w[0] == "TYPE") {
      types = values;
    } else if (w[0] == "COUNT") {
      if (values.size() != h.fields.size()) lines.fail("COUNT must have one entry per field");
      for (std::size_t i = 0; i < values.size(); ++i)
        h.fields[i].count = parseCount(values[i], lines, "COUNT");
    } else if (w[0] == "WIDTH" && values.size() == 1) {
      h.width = parseCount(values[0], lines, "WIDTH");
    } else if (w[0] == "HEIGHT" && values.size() == 1) {
      h.height = parseCount(values[0], lines, "HEIGHT");
    } else if (w[0] == "POINTS" && values.size() == 1) {
      h.points = parseCount(values[0], lines, "POINTS");
      h.pointsGiven = true;
    } else if (w[0] == "DATA" && values.size() == 1) {
      h.data = std::string(values[0]);
      if (h.fields.empty()) lines.fail("the PCD header has no FIELDS line");
      pcdFieldTypes(h, sizes, types, lines);
      if (!h.pointsGiven) h.points = h.width * h.height;
      return h;
    } else {
      lines.fail("unknown PCD header line '" + std::string(*line) + "'");
    }
  }
  lines.fail("the PCD header has no DATA line");
}

CloudPoints pcdCloud(std::string_view bytes, const std::string& source, std::size_t maxPoints) {
  HeaderLines lines(bytes, source);
  const PcdHeader h = pcdHeader(lines);
  if (h.data != "ascii" && h.data != "binary")
    throw FileError(source + ": PCD DATA '" + h.data + "' is not supported (ascii, binary)");
  std::size_t axes[3] = {}, offsets[3] = {}, values = 0, stride = 0;
  ScalarType types[3];
  bool found[3] = {false, false, false};
  for (std::size_t i = 0; i < h.fields.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      if (h.fields[i].name == std::string(1, static_cast<char>('x' + a))) {
        axes[a] = values;
        offsets[a] = stride;
        types[a] = h.fields[i].type;
        found[a] = true;
        if (h.fields[i].type.kind != 'f')
          throw FileError(source + ": PCD field '" + h.fields[i].name + "' must be of TYPE F");
      }
    }
    if (h.fields[i].count == 0 || h.fields[i].count > 1024)
      throw FileError(source + ": PCD field '" + h.fields[i].name + "' has COUNT " +
                      count(h.fields[i].count));
    values += h.fields[i].count;
    stride += h.fields[i].count * h.fields[i].type.size;
  }
  for (int a = 0; a < 3; ++a) {
    if (!found[a])
      throw FileError(source + ": the PCD file has no '" +
                      std::string(1, static_cast<char>('x' + a)) + "' field");
  }
  // An organised cloud (an image's pixels) marks the camera's missing returns with NaN.
  const bool organised = h.height > 1;
  CloudPoints cloud;
  auto keep = [&](const Eigen::Vector3d& p, std::size_t i, const std::string& where) {
    if (p.allFinite()) {
      cloud.points.push_back(p);
    } else if (!organised) {
      throw FileError(where + ": point " + count(i) + " is not finite");
    }
  };
  if (h.data == "binary") {
    const std::string_view data = lines.rest();
    if (h.points > 0 && stride > data.size() / h.points)
      throw FileError(source + ": truncated PCD data (" + count(data.size()) + " bytes for " +
                      count(h.points) + " points of " + count(stride) + " bytes)");
    requireFewEnough(h.points, maxPoints, source);
    cloud.points.reserve(h.points);
    for (std::size_t i = 0; i < h.points; ++i) {
      const char* p = data.data() + i * stride;
      keep({readScalar(p + offsets[0], types[0]), readScalar(p + offsets[1], types[1]),
            readScalar(p + offsets[2], types[2])},
           i, source);
    }
    return cloud;
  }
  requireFewEnough(h.points, maxPoints, source);
  cloud.points.reserve(std::min(h.points, bytes.size() / 6));
  for (std::size_t i = 0; i < h.points; ++i) {
    const auto line = lines.next();
    if (!line)
      throw FileError(source + ": truncated PCD data: " + count(i) + " of " + count(h.points) +
                      " points");
    const auto w = words(*line);
    if (w.size() != values)
      lines.fail("expected " + count(values) + " values, found " + count(w.size()));
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) {
      const auto value = parseNumber(w[axes[a]]);
      if (!value) lines.fail("'" + std::string(w[axes[a]]) + "' is not a number");
      p[a] = *value;
    }
    keep(p, i, lines.where());
  }
  return cloud;
}

}  // namespace

CloudFormat cloudFormatOf(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".npy") return CloudFormat::Npy;
  if (ext == ".ply") return CloudFormat::Ply;
  if (ext == ".pcd") return CloudFormat::Pcd;
  if (ext == ".bt") return CloudFormat::OctomapBinary;
  if (ext == ".ot") return CloudFormat::OctomapFull;
  throw FileError(path.string() + ": unknown point cloud format '" + ext +
                  "' (expected .npy, .ply, .pcd, .bt or .ot)");
}

CloudFile parseCloudFile(std::string_view bytes, CloudFormat format, const std::string& source,
                         std::size_t maxPoints) {
  CloudFile file;
  switch (format) {
    case CloudFormat::Npy:
      file.points = npyCloud(bytes, source, maxPoints);
      break;
    case CloudFormat::Ply:
      file.points = plyCloud(bytes, source, maxPoints);
      break;
    case CloudFormat::Pcd:
      file.points = pcdCloud(bytes, source, maxPoints);
      break;
    case CloudFormat::OctomapBinary:
    case CloudFormat::OctomapFull: {
      OctomapVoxels voxels =
          octomapVoxels(bytes, format == CloudFormat::OctomapBinary, source, maxPoints);
      file.points.points = std::move(voxels.centres);
      file.voxelSize = voxels.resolution;
      break;
    }
  }
  file.points.source = source;
  return file;
}

CloudFile readCloudFile(const std::filesystem::path& path, std::size_t maxPoints) {
  const CloudFormat format = cloudFormatOf(path);
  return parseCloudFile(readFile(path, "point cloud file"), format, path.string(), maxPoints);
}

}  // namespace fastron
