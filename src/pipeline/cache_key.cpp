#include "cache_key.h"

#include <cstdio>
#include <string>
#include <variant>

#include "fastron/geometry/point_kinematics.h"
#include "fastron/pipeline/self_model.h"

namespace fastron::pipeline {
namespace {

void hashShape(Hash& h, const Shape& shape) {
  h.value(shape.index());
  if (const auto* box = std::get_if<Box>(&shape)) h.doubles(box->size.data(), 3);
  if (const auto* sphere = std::get_if<Sphere>(&shape)) h.value(sphere->radius);
  if (const auto* cylinder = std::get_if<Cylinder>(&shape)) {
    h.value(cylinder->radius);
    h.value(cylinder->length);
  }
  if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    h.value(capsule->radius);
    h.value(capsule->length);
  }
  if (const auto* mesh = std::get_if<Mesh>(&shape)) {
    for (const Eigen::Vector3d& v : mesh->mesh->vertices) h.doubles(v.data(), 3);
    for (const Eigen::Vector3i& t : mesh->mesh->triangles) h.bytes(t.data(), 3 * sizeof(int));
  }
}

}  // namespace

void hashRobotCollisions(Hash& h, const Robot& robot) {
  h.value(kinematicsChecksum(robot));
  for (const LinkShape& shape : robot.shapes()) {
    h.value(shape.link);
    h.doubles(shape.origin.matrix().data(), 16);
    hashShape(h, shape.shape);
  }
  for (const auto& [a, b] : robot.selfCollisionPairs({})) {  // adjacency and allowed pairs
    h.value(a);
    h.value(b);
  }
}

std::filesystem::path cacheFile(const std::filesystem::path& directory, const Robot& robot,
                                std::uint64_t key, std::string_view extension) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(key));
  return (directory.empty() ? defaultCacheDirectory() : directory) /
         (robot.name() + "-" + hex + "." + std::string(extension));
}

}  // namespace fastron::pipeline
