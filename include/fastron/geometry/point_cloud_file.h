#pragma once
// Sensed obstacles from files: point clouds (.npy, .ply, .pcd) and OctoMaps (.bt, .ot), as
// docs/geometry.md ("Point clouds and OctoMaps") describes them.

#include <filesystem>
#include <string>
#include <string_view>

#include "fastron/core/export.h"
#include "fastron/geometry/shapes.h"

namespace FASTRON_API fastron {

/// The formats a cloud is read from.
enum class CloudFormat { Npy, Ply, Pcd, OctomapBinary, OctomapFull };

/// The format of `path` by its extension (.npy, .ply, .pcd, .bt, .ot); throws FileError naming the
/// file for any other.
CloudFormat cloudFormatOf(const std::filesystem::path& path);

/// Points read from a file, and for an OctoMap the edge of its smallest voxels (0 for a cloud).
struct CloudFile {
  CloudPoints points;
  double voxelSize = 0;
};

/// Reads the points of a cloud file (in the file's frame, metres):
/// - .npy: an (n, 3) array of float64, float32 or integers; n may be 0.
/// - .ply: format ascii 1.0 or binary_little_endian 1.0, the `vertex` element's x, y, z
///   properties (any numeric type); elements before `vertex` are skipped.
/// - .pcd: DATA ascii or binary, the x, y, z fields (F 4 or 8); in an organised cloud (HEIGHT > 1)
///   points with a NaN coordinate are the camera's missing returns and are skipped.
/// - .bt / .ot: an OctoMap OcTree's occupied voxels (occupancy above the tree's threshold), each
///   pruned leaf expanded into voxels of the map's resolution; the centre of each is a point.
/// Throws FileError naming the file (and line, for text) of the first problem: unknown or
/// malformed header, missing field, a point that is not finite, data shorter than declared (checked
/// before anything is allocated), or more than `maxPoints` points (an OctoMap of a few bytes can
/// describe millions of voxels).
inline constexpr std::size_t kMaxCloudPoints = 50'000'000;
CloudFile readCloudFile(const std::filesystem::path& path, std::size_t maxPoints = kMaxCloudPoints);

/// The same readers on the bytes of a file; errors name `source` as they would the file.
CloudFile parseCloudFile(std::string_view bytes, CloudFormat format, const std::string& source,
                         std::size_t maxPoints = kMaxCloudPoints);

}  // namespace fastron
