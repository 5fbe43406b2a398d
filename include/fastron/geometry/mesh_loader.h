#pragma once
// Mesh files (STL, OBJ, DAE and every other format assimp reads) as triangle meshes.

#include <Eigen/Core>
#include <filesystem>
#include <memory>

#include "fastron/core/export.h"
#include "fastron/geometry/shapes.h"

namespace FASTRON_API fastron {

/// Reads every mesh of the file's scene graph with its node transforms applied, then scales it.
/// Throws FileError naming the file when it is missing, unreadable or has no triangles.
std::shared_ptr<const TriangleMesh> loadMesh(
    const std::filesystem::path& path, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

}  // namespace fastron
