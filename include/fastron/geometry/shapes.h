#pragma once
// Collision shapes of robot links and obstacles. Every shape is centred on its own frame; the
// axis of cylinders and capsules is the frame's z axis.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

struct Box {
  Eigen::Vector3d size;  ///< full extents along x, y, z
};
struct Sphere {
  double radius;
};
struct Cylinder {
  double radius, length;  ///< length along z, centred
};
/// A cylinder of `length` along z with a hemisphere of `radius` on each end.
struct Capsule {
  double radius, length;  ///< length of the cylinder part only
};

/// A triangle mesh, already scaled, in the shape's frame.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::string source;  ///< the file it came from, for messages
};
struct Mesh {
  std::shared_ptr<const TriangleMesh> mesh;
};

using Shape = std::variant<Box, Sphere, Cylinder, Capsule, Mesh>;

/// Throws InvalidArgument naming `context` unless every size is finite and positive (a capsule's
/// cylinder part may be 0: a sphere) and a mesh has triangles.
void validate(const Shape& shape, const std::string& context);

/// The shape grown by `padding` in every direction (a mesh cannot be padded: InvalidArgument).
Shape inflate(const Shape& shape, double padding);

/// "box 0.2 x 0.2 x 0.2", "sphere r 0.1", ...
std::string describe(const Shape& shape);

/// Radius of the smallest sphere about the shape's origin that contains it.
double boundingRadius(const Shape& shape);

/// Half the extents of the smallest box about the shape's origin, aligned with its frame, that
/// contains it.
Eigen::Vector3d halfExtents(const Shape& shape);

}  // namespace fastron
