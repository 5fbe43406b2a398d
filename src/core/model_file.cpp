#include "fastron/core/model_file.h"

#include <zlib.h>

#include <array>
#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fastron/core/error.h"

namespace fastron {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the model file is little-endian; add byte swapping for this platform");

constexpr std::array<char, 8> kMagic = {'F', 'A', 'S', 'T', 'R', 'O', 'N', '\0'};
// magic, version, dimension, kernel type, reserved, gamma
constexpr std::size_t kHeaderSize = 8 + 4 + 4 + 4 + 4 + 8;

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
  std::vector<char>& bytes() { return bytes_; }

 private:
  std::vector<char> bytes_;
};

class Reader {
 public:
  Reader(const std::vector<char>& bytes, const std::string& file) : bytes_(bytes), file_(file) {}
  template <class T>
  T get() {
    T value{};
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  double getFinite(const char* field) {
    const auto value = get<double>();
    if (!std::isfinite(value)) throw FileError(file_ + ": " + field + " is not finite");
    return value;
  }

 private:
  const std::vector<char>& bytes_;
  const std::string& file_;
  std::size_t pos_ = 0;
};

}  // namespace

void saveModel(const Model& model, const std::filesystem::path& path) {
  const std::size_t d = model.dim();
  Writer w;
  w.putBytes(kMagic.data(), kMagic.size());
  w.put<std::uint32_t>(kModelFileVersion);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(d));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(model.kernel().type));
  w.put<std::uint32_t>(0);
  w.put<double>(model.kernel().gamma);
  for (std::size_t j = 0; j < d; ++j)
    w.put<double>(model.limits().lower()[static_cast<Eigen::Index>(j)]);
  for (std::size_t j = 0; j < d; ++j)
    w.put<double>(model.limits().upper()[static_cast<Eigen::Index>(j)]);
  w.put<std::uint64_t>(model.supportCount());
  const Eigen::MatrixXd& s = model.supportPoints();
  for (Eigen::Index i = 0; i < s.rows(); ++i) {
    for (Eigen::Index j = 0; j < s.cols(); ++j) w.put<double>(s(i, j));
  }
  for (Eigen::Index i = 0; i < model.weights().size(); ++i) w.put<double>(model.weights()[i]);
  w.put<std::uint32_t>(crc32Of(w.bytes().data(), w.bytes().size()));

  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(w.bytes().data(), static_cast<std::streamsize>(w.bytes().size()));
  out.close();
  if (!out) throw FileError(path.string() + ": cannot write model file");
}

Model loadModel(const std::filesystem::path& path, std::optional<std::size_t> expectedDim) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(file + ": cannot open model file");
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());

  if (bytes.size() < kMagic.size() ||
      std::memcmp(bytes.data(), kMagic.data(), kMagic.size()) != 0) {
    throw FileError(file + ": not a Fastron model file (bad magic bytes)");
  }
  if (bytes.size() < kHeaderSize) {
    throw FileError(file + ": truncated model file (" + std::to_string(bytes.size()) +
                    " bytes, the header alone needs " + std::to_string(kHeaderSize) + ")");
  }
  Reader r(bytes, file);
  r.get<std::array<char, 8>>();
  const auto version = r.get<std::uint32_t>();
  if (version != kModelFileVersion) {
    throw FileError(file + ": unsupported model file version " + std::to_string(version) +
                    " (this build reads version " + std::to_string(kModelFileVersion) + ")");
  }
  const std::size_t dim = r.get<std::uint32_t>();
  if (dim == 0 || dim > kMaxDimension) {
    throw FileError(file + ": invalid dimension " + std::to_string(dim));
  }
  const std::size_t countOffset = kHeaderSize + 2 * sizeof(double) * dim;
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
  const std::size_t expectedSize = countOffset + 8 + 8 * count * (dim + 1) + 4;
  if (bytes.size() != expectedSize) {
    throw FileError(file + ": " +
                    (bytes.size() < expectedSize ? "truncated" : "trailing bytes in") +
                    " model file (" + std::to_string(bytes.size()) + " bytes, expected " +
                    std::to_string(expectedSize) + ")");
  }
  std::uint32_t storedCrc = 0;
  std::memcpy(&storedCrc, bytes.data() + expectedSize - 4, sizeof(storedCrc));
  if (storedCrc != crc32Of(bytes.data(), expectedSize - 4)) {
    throw FileError(file + ": corrupt model file (checksum mismatch)");
  }
  if (expectedDim && *expectedDim != dim) {
    throw FileError(file + ": model has dimension " + std::to_string(dim) + " but " +
                    std::to_string(*expectedDim) + " was expected");
  }

  const auto kernelType = r.get<std::uint32_t>();
  if (kernelType > static_cast<std::uint32_t>(KernelType::Gaussian)) {
    throw FileError(file + ": unknown kernel type " + std::to_string(kernelType));
  }
  r.get<std::uint32_t>();  // reserved
  Kernel kernel{static_cast<KernelType>(kernelType), r.getFinite("gamma")};
  const auto d = static_cast<Eigen::Index>(dim);
  Eigen::VectorXd lower(d), upper(d);
  for (Eigen::Index j = 0; j < d; ++j) lower[j] = r.getFinite("lower joint limit");
  for (Eigen::Index j = 0; j < d; ++j) upper[j] = r.getFinite("upper joint limit");
  r.get<std::uint64_t>();
  const auto n = static_cast<Eigen::Index>(count);
  Eigen::MatrixXd support(n, d);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < d; ++j) support(i, j) = r.getFinite("support point value");
  }
  Eigen::VectorXd weights(n);
  for (Eigen::Index i = 0; i < n; ++i) weights[i] = r.getFinite("weight");
  try {
    return Model(JointLimits(std::move(lower), std::move(upper)), kernel, std::move(support),
                 std::move(weights));
  } catch (const InvalidArgument& e) {
    throw FileError(file + ": invalid model: " + e.what());
  }
}

}  // namespace fastron
