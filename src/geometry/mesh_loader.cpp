#include "fastron/geometry/mesh_loader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <functional>

#include "fastron/core/error.h"

namespace fastron {

std::shared_ptr<const TriangleMesh> loadMesh(const std::filesystem::path& path,
                                             const Eigen::Vector3d& scale) {
  const std::string file = path.string();
  if (!std::filesystem::is_regular_file(path)) throw FileNotFound(file + ": mesh file not found");
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(
      file, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw FileError(file + ": cannot read mesh: " + importer.GetErrorString());
  }

  auto mesh = std::make_shared<TriangleMesh>();
  mesh->source = file;
  // Walk the node tree so every mesh gets its node's transform (DAE files rely on it).
  std::function<void(const aiNode*, const aiMatrix4x4&)> visit = [&](const aiNode* node,
                                                                     const aiMatrix4x4& parent) {
    const aiMatrix4x4 transform = parent * node->mTransformation;
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const aiMesh* part = scene->mMeshes[node->mMeshes[m]];
      const int offset = static_cast<int>(mesh->vertices.size());
      for (unsigned v = 0; v < part->mNumVertices; ++v) {
        const aiVector3D p = transform * part->mVertices[v];
        mesh->vertices.emplace_back(p.x * scale.x(), p.y * scale.y(), p.z * scale.z());
      }
      for (unsigned f = 0; f < part->mNumFaces; ++f) {
        const aiFace& face = part->mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines carry no volume
        mesh->triangles.emplace_back(offset + static_cast<int>(face.mIndices[0]),
                                     offset + static_cast<int>(face.mIndices[1]),
                                     offset + static_cast<int>(face.mIndices[2]));
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) visit(node->mChildren[c], transform);
  };
  visit(scene->mRootNode, aiMatrix4x4());
  if (mesh->triangles.empty()) throw FileError(file + ": mesh has no triangles");
  if (!scale.allFinite() || (scale.array() == 0).any()) {
    throw FileError(file + ": invalid mesh scale");
  }
  return mesh;
}

}  // namespace fastron
