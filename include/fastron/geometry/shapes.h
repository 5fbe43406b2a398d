#pragma once
// Collision shapes of robot links and obstacles. Every shape is centred on its own frame; the
// axis of cylinders and capsules is the frame's z axis.

#include <Eigen/Core>
#include <Eigen/Geometry>
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

/// Points in the shape's frame (metres), e.g. a depth camera's, already filtered
/// (point_cloud.h).
struct CloudPoints {
  std::vector<Eigen::Vector3d> points;
  std::string source;  ///< the file or sensor it came from, for messages
};
/// A sensed obstacle: a ball of `radius` about every point. No points: an obstacle that nothing
/// touches.
struct PointCloud {
  std::shared_ptr<const CloudPoints> cloud;
  double radius;
};

using Shape = std::variant<Box, Sphere, Cylinder, Capsule, Mesh, PointCloud>;

/// Throws InvalidArgument naming `context` unless every size is finite and positive (a capsule's
/// cylinder part may be 0: a sphere), a mesh has triangles and a cloud's points are finite.
void validate(const Shape& shape, const std::string& context);

/// The shape grown by `padding` in every direction (a cloud by its radius; a mesh cannot be padded:
/// InvalidArgument).
Shape inflate(const Shape& shape, double padding);

/// "box 0.2 x 0.2 x 0.2", "sphere r 0.1", ...
std::string describe(const Shape& shape);

/// Radius of the smallest sphere about the shape's origin that contains it (0 for an empty cloud).
double boundingRadius(const Shape& shape);

/// The smallest box aligned with the shape's frame that contains it: about the origin for a
/// primitive, around its vertices or points for a mesh or a cloud (off the origin when they are,
/// as the mesh Panda's forearm is). Empty for an empty mesh or cloud.
Eigen::AlignedBox3d shapeBounds(const Shape& shape);

}  // namespace fastron
