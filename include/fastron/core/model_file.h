#pragma once
// The versioned binary model file.
//
// Layout (little-endian): magic "FASTRON\0", u32 version (1), u32 dimension d, u32 kernel type,
// u32 reserved (0), f64 gamma, f64 lower[d], f64 upper[d], u64 support count n,
// f64 support points [n * d] (input space, row by row), f64 weights [n],
// u32 CRC-32 of every preceding byte.

#include <cstddef>
#include <filesystem>
#include <optional>

#include "fastron/core/model.h"

namespace fastron {

inline constexpr std::uint32_t kModelFileVersion = 1;

/// Writes `model` to `path`; throws FileError if the file cannot be written.
void saveModel(const Model& model, const std::filesystem::path& path);

/// Reads a model; throws FileError naming the file and the problem (missing, truncated, not a
/// model file, unsupported version, corrupt, invalid contents) and, when `expectedDim` is given,
/// a dimension different from it.
Model loadModel(const std::filesystem::path& path,
                std::optional<std::size_t> expectedDim = std::nullopt);

}  // namespace fastron
