#include "fastron/core/model_file.h"

#include <zlib.h>

#include <array>
#include <bit>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/error.h"
#include "fastron/core/file_io.h"

namespace fastron {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the model file is little-endian; add byte swapping for this platform");

constexpr std::array<char, 8> kMagic = {'F', 'A', 'S', 'T', 'R', 'O', 'N', '\0'};
constexpr std::size_t kVersionEnd = 8 + 4 + 4;  // magic, version, dimension
// Version 1: magic, version, dimension, kernel type, reserved, gamma.
constexpr std::size_t kHeaderSizeV1 = kVersionEnd + 4 + 4 + 8;
constexpr std::size_t kMaxNameBytes = 4096;
constexpr std::size_t kMaxControlPoints = kMaxFeatureDimension / 3;

std::uint32_t crc32Of(const char* data, std::size_t size) {
  return static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(data), static_cast<uInt>(size)));
}

class Writer {
 public:
  template <class T>
  void put(T value) {
    const auto* p = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void putBytes(const char* p, std::size_t n) { bytes_.insert(bytes_.end(), p, p + n); }
  void putString(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    putBytes(s.data(), s.size());
  }
  std::vector<char>& bytes() { return bytes_; }

 private:
  std::vector<char> bytes_;
};

/// Reads fields in order from bytes [0, end); running past `end` means the contents disagree with
/// themselves (the size and checksum were checked before), which is reported as invalid.
class Reader {
 public:
  Reader(std::string_view bytes, std::size_t end, const std::string& file)
      : bytes_(bytes), end_(end), file_(file) {}
  template <class T>
  T get(const char* field) {
    need(sizeof(T), field);
    T value{};
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  double getFinite(const char* field) {
    const auto value = get<double>(field);
    if (!std::isfinite(value)) throw FileError(file_ + ": " + field + " is not finite");
    return value;
  }
  std::string getString(const char* field) {
    const auto size = get<std::uint32_t>(field);
    if (size > kMaxNameBytes) {
      throw FileError(file_ + ": invalid model: " + field + " of " + std::to_string(size) +
                      " bytes");
    }
    need(size, field);
    std::string s(bytes_.data() + pos_, size);
    pos_ += size;
    return s;
  }
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return end_ - pos_; }

 private:
  void need(std::size_t n, const char* field) const {
    if (end_ - pos_ < n) {
      throw FileError(file_ + ": invalid model: the file ends inside " + std::string(field));
    }
  }
  std::string_view bytes_;
  std::size_t end_;
  const std::string& file_;
  std::size_t pos_ = 0;
};

void checkChecksum(std::string_view bytes, std::size_t size, const std::string& file) {
  std::uint32_t stored = 0;
  std::memcpy(&stored, bytes.data() + size - 4, sizeof(stored));
  if (stored != crc32Of(bytes.data(), size - 4)) {
    throw FileError(file + ": corrupt model file (checksum mismatch)");
  }
}

std::string sizeMismatch(const std::string& file, std::size_t actual, std::size_t expected) {
  return file + ": " + (actual < expected ? "truncated" : "trailing bytes in") + " model file (" +
         std::to_string(actual) + " bytes, expected " + std::to_string(expected) + ")";
}

/// Everything a file holds, parsed and checked for size and checksum.
struct Contents {
  ModelFileHeader header;
  Kernel kernel;
  Eigen::VectorXd lower, upper;
  Configurations support;  // joint values
  Eigen::VectorXd weights;
};

Kernel readKernel(Reader& r, std::uint32_t type, const std::string& file) {
  if (type > static_cast<std::uint32_t>(KernelType::Gaussian)) {
    throw FileError(file + ": unknown kernel type " + std::to_string(type));
  }
  return {static_cast<KernelType>(type), r.getFinite("gamma")};
}

void readLimits(Reader& r, Contents& c) {
  const auto d = static_cast<Eigen::Index>(c.header.dim);
  c.lower.resize(d);
  c.upper.resize(d);
  for (Eigen::Index j = 0; j < d; ++j) c.lower[j] = r.getFinite("lower joint limit");
  for (Eigen::Index j = 0; j < d; ++j) c.upper[j] = r.getFinite("upper joint limit");
}

/// Support count, then n * d values and n weights, which must fill the file up to the checksum.
void readSupport(Reader& r, Contents& c, const std::string& file) {
  const auto count = r.get<std::uint64_t>("support count");
  const std::size_t d = c.header.dim;
  if (count > r.remaining() / (8 * (d + 1)) || r.remaining() != 8 * count * (d + 1)) {
    throw FileError(file + ": invalid model: " + std::to_string(count) + " support points of " +
                    std::to_string(d) + " values do not fill the remaining " +
                    std::to_string(r.remaining()) + " bytes");
  }
  const auto n = static_cast<Eigen::Index>(count);
  c.support.resize(n, static_cast<Eigen::Index>(d));
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < c.support.cols(); ++j) {
      c.support(i, j) = r.getFinite("support point value");
    }
  }
  c.weights.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) c.weights[i] = r.getFinite("weight");
}

Contents readVersion1(std::string_view bytes, Contents c, const std::string& file) {
  const std::size_t dim = c.header.dim;
  const std::size_t countOffset = kHeaderSizeV1 + 2 * sizeof(double) * dim;
  if (bytes.size() < countOffset + 8) {
    throw FileError(file + ": truncated model file (" + std::to_string(bytes.size()) + " bytes)");
  }
  std::uint64_t count = 0;
  std::memcpy(&count, bytes.data() + countOffset, sizeof(count));
  const std::size_t maxCount = (bytes.size() - countOffset) / (8 * (dim + 1));
  if (count > maxCount) {
    throw FileError(file + ": truncated model file (" + std::to_string(bytes.size()) +
                    " bytes for " + std::to_string(count) + " support points)");
  }
  const std::size_t expected = countOffset + 8 + 8 * count * (dim + 1) + 4;
  if (bytes.size() != expected) throw FileError(sizeMismatch(file, bytes.size(), expected));
  checkChecksum(bytes, expected, file);

  Reader r(bytes, expected - 4, file);
  r.get<std::array<char, kVersionEnd>>("header");
  const auto kernelType = r.get<std::uint32_t>("kernel type");
  r.get<std::uint32_t>("reserved");
  c.kernel = readKernel(r, kernelType, file);
  readLimits(r, c);
  readSupport(r, c, file);
  // Version 1 stored support points in input space [-1, 1]^d.
  try {
    c.support = JointLimits(c.lower, c.upper).toJoint(c.support);
  } catch (const InvalidArgument& e) {
    throw FileError(file + ": invalid model: " + e.what());
  }
  return c;
}

/// Versions 2 and 3 (which adds the kernel block).
Contents readVersion2or3(std::string_view bytes, Contents c, const std::string& file) {
  constexpr std::size_t kFixed = kVersionEnd + 8;
  if (bytes.size() < kFixed + 4) {
    throw FileError(file + ": truncated model file (" + std::to_string(bytes.size()) +
                    " bytes, the header alone needs " + std::to_string(kFixed + 4) + ")");
  }
  std::uint64_t size = 0;
  std::memcpy(&size, bytes.data() + kVersionEnd, sizeof(size));
  if (bytes.size() != size) throw FileError(sizeMismatch(file, bytes.size(), size));
  checkChecksum(bytes, bytes.size(), file);

  Reader r(bytes, bytes.size() - 4, file);
  r.get<std::array<char, kFixed>>("header");
  const auto kernelType = r.get<std::uint32_t>("kernel type");
  const auto featureKind = r.get<std::uint32_t>("feature kind");
  if (featureKind > static_cast<std::uint32_t>(FeatureKind::Kinematic)) {
    throw FileError(file + ": unknown feature kind " + std::to_string(featureKind));
  }
  c.header.features = static_cast<FeatureKind>(featureKind);
  c.kernel = readKernel(r, kernelType, file);
  if (c.header.version >= 3) {
    c.kernel.block = r.get<std::uint32_t>("kernel block");
    c.kernel.wholeShare = r.getFinite("kernel whole-vector share");
  }
  readLimits(r, c);
  if (c.header.features == FeatureKind::Kinematic) {
    KinematicsDescription& k = c.header.kinematics;
    k.checksum = r.get<std::uint64_t>("kinematics checksum");
    k.robot = r.getString("robot name");
    const auto joints = r.get<std::uint32_t>("joint count");
    if (joints != c.header.dim) {
      throw FileError(file + ": invalid model: " + std::to_string(joints) +
                      " joint names for dimension " + std::to_string(c.header.dim));
    }
    for (std::uint32_t j = 0; j < joints; ++j) k.joints.push_back(r.getString("joint name"));
    const auto points = r.get<std::uint32_t>("control point count");
    if (points == 0 || points > kMaxControlPoints) {
      throw FileError(file + ": invalid model: " + std::to_string(points) + " control points");
    }
    for (std::uint32_t p = 0; p < points; ++p) {
      ControlPoint point;
      point.link = r.getString("control point link");
      for (int a = 0; a < 3; ++a) point.offset[a] = r.getFinite("control point offset");
      k.points.push_back(std::move(point));
    }
  }
  readSupport(r, c, file);
  return c;
}

Contents readContents(std::string_view bytes, const std::string& file) {
  if (bytes.size() < kMagic.size() ||
      std::memcmp(bytes.data(), kMagic.data(), kMagic.size()) != 0) {
    throw FileError(file + ": not a Fastron model file (bad magic bytes)");
  }
  if (bytes.size() < kVersionEnd) {
    throw FileError(file + ": truncated model file (" + std::to_string(bytes.size()) +
                    " bytes, the header alone needs " + std::to_string(kVersionEnd) + ")");
  }
  Contents c;
  std::uint32_t dim = 0;
  std::memcpy(&c.header.version, bytes.data() + 8, 4);
  std::memcpy(&dim, bytes.data() + 12, 4);
  if (c.header.version < 1 || c.header.version > 3) {
    throw FileError(file + ": unsupported model file version " + std::to_string(c.header.version) +
                    " (this build reads versions 1 to 3)");
  }
  if (dim == 0 || dim > kMaxDimension) {
    throw FileError(file + ": invalid dimension " + std::to_string(dim));
  }
  c.header.dim = dim;
  return c.header.version == 1 ? readVersion1(bytes, std::move(c), file)
                               : readVersion2or3(bytes, std::move(c), file);
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

std::string pointText(const ControlPoint& p) {
  std::ostringstream s;
  s << p.link << " + (" << p.offset.x() << ", " << p.offset.y() << ", " << p.offset.z() << ")";
  return s.str();
}

/// Names the first difference between the kinematics a model was trained with and those given.
void checkKinematics(const KinematicsDescription& trained, const KinematicsDescription& given,
                     const std::string& file) {
  const std::string prefix = file + ": the model was trained ";
  if (trained.robot != given.robot) {
    throw FileError(prefix + "for robot '" + trained.robot + "', not '" + given.robot + "'");
  }
  if (trained.joints != given.joints) {
    throw FileError(prefix + "on joints " + joined(trained.joints) + ", not " +
                    joined(given.joints));
  }
  if (trained.points.size() != given.points.size()) {
    throw FileError(prefix + "with " + std::to_string(trained.points.size()) +
                    " control points, not " + std::to_string(given.points.size()));
  }
  for (std::size_t p = 0; p < trained.points.size(); ++p) {
    if (trained.points[p] != given.points[p]) {
      throw FileError(prefix + "with control point " + std::to_string(p) + " at " +
                      pointText(trained.points[p]) + ", not " + pointText(given.points[p]));
    }
  }
  if (trained.checksum != given.checksum) {
    throw FileError(prefix + "on a robot '" + trained.robot +
                    "' whose kinematics (joint origins, axes or types) differ from the one given");
  }
}

}  // namespace

void saveModel(const Model& model, const std::filesystem::path& path) {
  const std::size_t d = model.dim();
  const FeatureMap& features = model.features();
  Writer w;
  w.putBytes(kMagic.data(), kMagic.size());
  w.put<std::uint32_t>(kModelFileVersion);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(d));
  w.put<std::uint64_t>(0);  // the file's size, filled in below
  w.put<std::uint32_t>(static_cast<std::uint32_t>(model.kernel().type));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(features.kind()));
  w.put<double>(model.kernel().gamma);
  w.put<std::uint32_t>(model.kernel().block);
  w.put<double>(model.kernel().wholeShare);
  for (std::size_t j = 0; j < d; ++j)
    w.put<double>(model.limits().lower()[static_cast<Eigen::Index>(j)]);
  for (std::size_t j = 0; j < d; ++j)
    w.put<double>(model.limits().upper()[static_cast<Eigen::Index>(j)]);
  if (features.kind() == FeatureKind::Kinematic) {
    const KinematicsDescription k = features.kinematics()->description();
    w.put<std::uint64_t>(k.checksum);
    w.putString(k.robot);
    w.put<std::uint32_t>(static_cast<std::uint32_t>(k.joints.size()));
    for (const auto& joint : k.joints) w.putString(joint);
    w.put<std::uint32_t>(static_cast<std::uint32_t>(k.points.size()));
    for (const auto& point : k.points) {
      w.putString(point.link);
      for (int a = 0; a < 3; ++a) w.put<double>(point.offset[a]);
    }
  }
  w.put<std::uint64_t>(model.supportCount());
  const Configurations& s = model.supportConfigurations();
  for (Eigen::Index i = 0; i < s.rows(); ++i) {
    for (Eigen::Index j = 0; j < s.cols(); ++j) w.put<double>(s(i, j));
  }
  for (Eigen::Index i = 0; i < model.weights().size(); ++i) w.put<double>(model.weights()[i]);
  const std::uint64_t size = w.bytes().size() + 4;
  std::memcpy(w.bytes().data() + kVersionEnd, &size, sizeof(size));
  w.put<std::uint32_t>(crc32Of(w.bytes().data(), w.bytes().size()));

  writeFileAtomically(path, std::string_view(w.bytes().data(), w.bytes().size()), "model file");
}

ModelFileHeader parseModelHeader(std::string_view bytes, const std::string& source) {
  return readContents(bytes, source).header;
}

ModelFileHeader readModelHeader(const std::filesystem::path& path) {
  return parseModelHeader(readFile(path, "model file"), path.string());
}

Model loadModel(const std::filesystem::path& path, std::optional<std::size_t> expectedDim,
                std::shared_ptr<const PointKinematics> kinematics) {
  return parseModel(readFile(path, "model file"), path.string(), expectedDim,
                    std::move(kinematics));
}

Model parseModel(std::string_view bytes, const std::string& source,
                 std::optional<std::size_t> expectedDim,
                 std::shared_ptr<const PointKinematics> kinematics) {
  const std::string& file = source;
  Contents c = readContents(bytes, file);
  if (expectedDim && *expectedDim != c.header.dim) {
    throw FileError(file + ": model has dimension " + std::to_string(c.header.dim) + " but " +
                    std::to_string(*expectedDim) + " was expected");
  }
  if (c.header.features == FeatureKind::Kinematic) {
    if (!kinematics) {
      throw FileError(file + ": the model uses task-space features of robot '" +
                      c.header.kinematics.robot + "'; load it with that robot (e.g. --robot " +
                      c.header.kinematics.robot + ")");
    }
    checkKinematics(c.header.kinematics, kinematics->description(), file);
  }
  try {
    JointLimits limits(std::move(c.lower), std::move(c.upper));
    FeatureMap features = c.header.features == FeatureKind::Kinematic
                              ? FeatureMap::kinematic(std::move(limits), std::move(kinematics))
                              : FeatureMap::jointScaling(std::move(limits));
    return Model(std::move(features), c.kernel, std::move(c.support), std::move(c.weights));
  } catch (const InvalidArgument& e) {
    throw FileError(file + ": invalid model: " + e.what());
  }
}

}  // namespace fastron
