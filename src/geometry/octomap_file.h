#pragma once
// OctoMap files (.bt and .ot of an OcTree) as the centres of their occupied voxels.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace fastron {

struct OctomapVoxels {
  std::vector<Eigen::Vector3d> centres;  ///< of every occupied voxel of the map's resolution
  double resolution = 0;                 ///< the voxels' edge (metres)
};

/// The occupied voxels of an OcTree file's bytes: `binary` for .bt (occupancy bits), else .ot
/// (the full format, log-odds per node; occupied at or above the tree's threshold). The data's
/// structure is checked before octomap reads it (octomap trusts it: a truncated or corrupt file
/// would make it read past the end or recurse without bound). Throws FileError naming `source`.
OctomapVoxels octomapVoxels(std::string_view bytes, bool binary, const std::string& source,
                            std::size_t maxVoxels);

}  // namespace fastron
