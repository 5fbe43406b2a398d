#include "fastron/geometry/shapes.h"

#include <cmath>
#include <cstdio>

#include "fastron/core/error.h"
#include "overloaded.h"

namespace fastron {
namespace {

void requirePositive(double value, const char* what, const std::string& context,
                     bool allowZero = false) {
  if (!std::isfinite(value) || value < 0 || (value == 0 && !allowZero)) {
    throw InvalidArgument(context + ": " + what + " must be a finite positive number, got " +
                          std::to_string(value));
  }
}

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

}  // namespace

void validate(const Shape& shape, const std::string& context) {
  std::visit(Overloaded{
                 [&](const Box& b) {
                   for (int i = 0; i < 3; ++i) requirePositive(b.size[i], "box size", context);
                 },
                 [&](const Sphere& s) { requirePositive(s.radius, "sphere radius", context); },
                 [&](const Cylinder& c) {
                   requirePositive(c.radius, "cylinder radius", context);
                   requirePositive(c.length, "cylinder length", context);
                 },
                 [&](const Capsule& c) {
                   requirePositive(c.radius, "capsule radius", context);
                   requirePositive(c.length, "capsule length", context, true);
                 },
                 [&](const Mesh& m) {
                   if (!m.mesh || m.mesh->triangles.empty()) {
                     throw InvalidArgument(context + ": mesh has no triangles");
                   }
                 },
                 [&](const PointCloud& c) {
                   requirePositive(c.radius, "point cloud radius", context);
                   if (!c.cloud) throw InvalidArgument(context + ": point cloud has no points");
                   const auto& points = c.cloud->points;
                   for (std::size_t i = 0; i < points.size(); ++i) {
                     if (!points[i].allFinite())
                       throw InvalidArgument(context + ": point " + std::to_string(i) +
                                             " of the cloud is not finite");
                   }
                 },
             },
             shape);
}

Shape inflate(const Shape& shape, double padding) {
  if (padding == 0) return shape;
  if (!std::isfinite(padding) || padding < 0) {
    throw InvalidArgument("padding must be finite and >= 0, got " + std::to_string(padding));
  }
  return std::visit(Overloaded{
                        [&](const Box& b) -> Shape { return Box{b.size.array() + 2 * padding}; },
                        [&](const Sphere& s) -> Shape { return Sphere{s.radius + padding}; },
                        [&](const Cylinder& c) -> Shape {
                          return Cylinder{c.radius + padding, c.length + 2 * padding};
                        },
                        [&](const Capsule& c) -> Shape {
                          return Capsule{c.radius + padding, c.length};
                        },
                        [&](const Mesh& m) -> Shape {
                          throw InvalidArgument("cannot pad the mesh " +
                                                (m.mesh ? m.mesh->source : std::string("(empty)")));
                        },
                        [&](const PointCloud& c) -> Shape {
                          return PointCloud{c.cloud, c.radius + padding};
                        },
                    },
                    shape);
}

std::string describe(const Shape& shape) {
  return std::visit(Overloaded{
                        [](const Box& b) {
                          return "box " + number(b.size.x()) + " x " + number(b.size.y()) + " x " +
                                 number(b.size.z());
                        },
                        [](const Sphere& s) { return "sphere r " + number(s.radius); },
                        [](const Cylinder& c) {
                          return "cylinder r " + number(c.radius) + " l " + number(c.length);
                        },
                        [](const Capsule& c) {
                          return "capsule r " + number(c.radius) + " l " + number(c.length);
                        },
                        [](const Mesh& m) {
                          return "mesh " + (m.mesh ? m.mesh->source : std::string()) + " (" +
                                 std::to_string(m.mesh ? m.mesh->triangles.size() : 0) +
                                 " triangles)";
                        },
                        [](const PointCloud& c) {
                          return "point cloud " + (c.cloud ? c.cloud->source : std::string()) +
                                 " (" + std::to_string(c.cloud ? c.cloud->points.size() : 0) +
                                 " points, r " + number(c.radius) + ")";
                        },
                    },
                    shape);
}

double boundingRadius(const Shape& shape) {
  return std::visit(Overloaded{
                        [](const Box& b) { return 0.5 * b.size.norm(); },
                        [](const Sphere& s) { return s.radius; },
                        [](const Cylinder& c) { return std::hypot(c.radius, 0.5 * c.length); },
                        [](const Capsule& c) { return c.radius + 0.5 * c.length; },
                        [](const Mesh& m) {
                          double r = 0;
                          for (const auto& v : m.mesh->vertices) r = std::max(r, v.norm());
                          return r;
                        },
                        [](const PointCloud& c) {
                          double r = 0;
                          for (const auto& p : c.cloud->points) r = std::max(r, p.norm());
                          return c.cloud->points.empty() ? 0.0 : r + c.radius;
                        },
                    },
                    shape);
}

Eigen::AlignedBox3d shapeBounds(const Shape& shape) {
  const auto about = [](const Eigen::Vector3d& half) { return Eigen::AlignedBox3d(-half, half); };
  return std::visit(Overloaded{
                        [&](const Box& b) { return about(b.size / 2); },
                        [&](const Sphere& s) { return about(Eigen::Vector3d::Constant(s.radius)); },
                        [&](const Cylinder& c) {
                          return about({c.radius, c.radius, c.length / 2});
                        },
                        [&](const Capsule& c) {
                          return about({c.radius, c.radius, c.length / 2 + c.radius});
                        },
                        [](const Mesh& m) {
                          Eigen::AlignedBox3d box;
                          for (const auto& v : m.mesh->vertices) box.extend(v);
                          return box;
                        },
                        [](const PointCloud& c) {
                          Eigen::AlignedBox3d box;
                          for (const auto& p : c.cloud->points) box.extend(p);
                          if (!box.isEmpty()) {
                            box.min().array() -= c.radius;
                            box.max().array() += c.radius;
                          }
                          return box;
                        },
                    },
                    shape);
}

}  // namespace fastron
