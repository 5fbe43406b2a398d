#pragma once
// The versioned binary model file.
//
// Version 3 (written; little-endian):
//   magic "FASTRON\0", u32 version (3), u32 dimension d (joint values per configuration),
//   u64 size of the whole file in bytes, u32 kernel type, u32 feature kind (0 joints, 1 fk),
//   f64 gamma, u32 kernel block (features per point term, 0 = one term: Kernel::block),
//   f64 the whole vector's share of the kernel (Kernel::wholeShare),
//   f64 lower[d], f64 upper[d] (joint limits),
//   for fk features only: u64 kinematics checksum, str robot, u32 joint count m,
//     str joint[m], u32 point count p, then p times (str link, f64 x, f64 y, f64 z),
//   u64 support count n, f64 support configurations [n * d] (joint values, row by row),
//   f64 weights [n], u32 CRC-32 of every preceding byte.
//   A str is a u32 byte count and that many bytes of UTF-8.
// Version 2 (still read): version 3 without the kernel block (its kernels have one term).
// Version 1 (still read): magic, u32 version (1), u32 d, u32 kernel type, u32 reserved (0),
//   f64 gamma, f64 lower[d], f64 upper[d], u64 n, f64 support points [n * d] in input space
//   [-1, 1]^d, f64 weights [n], u32 CRC-32; its features are joint scaling.

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/core/model.h"

namespace FASTRON_API fastron {

inline constexpr std::uint32_t kModelFileVersion = 3;

/// Writes `model` to `path` atomically (writeFileAtomically: a crash while saving leaves the old
/// file whole); throws FileError if the file cannot be written.
void saveModel(const Model& model, const std::filesystem::path& path);

/// What a model file says about its input, read without building the model: enough to build the
/// kinematics a task-space model needs before loading it.
struct ModelFileHeader {
  std::uint32_t version = 0;
  std::size_t dim = 0;
  FeatureKind features = FeatureKind::JointScaling;
  KinematicsDescription kinematics;  ///< fk only
};

/// Reads and checks a whole model file (size, checksum) and returns its header. Throws FileError
/// as loadModel does.
ModelFileHeader readModelHeader(const std::filesystem::path& path);

/// Reads a model; throws FileError naming the file and the problem (missing, truncated, not a
/// model file, unsupported version, corrupt, invalid contents) and, when `expectedDim` is given,
/// a dimension different from it. A model with task-space features needs `kinematics` whose
/// description (robot, joints, control points, checksum of the kinematics) equals the one the
/// model was trained with; a difference is refused with a message that names it. Kinematics given
/// for a joint-space model are not used.
Model loadModel(const std::filesystem::path& path,
                std::optional<std::size_t> expectedDim = std::nullopt,
                std::shared_ptr<const PointKinematics> kinematics = nullptr);

/// readModelHeader and loadModel on the bytes of a model file; errors name `source`.
ModelFileHeader parseModelHeader(std::string_view bytes, const std::string& source);
Model parseModel(std::string_view bytes, const std::string& source,
                 std::optional<std::size_t> expectedDim = std::nullopt,
                 std::shared_ptr<const PointKinematics> kinematics = nullptr);

}  // namespace fastron
