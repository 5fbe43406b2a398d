#include "fastron/geometry/scene_sensing.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "fastron/core/error.h"
#include "overloaded.h"

namespace fastron {
namespace {

constexpr double kNoHit = std::numeric_limits<double>::infinity();
constexpr std::size_t kMaxSurfacePoints = 50'000'000;

/// The smallest t >= 0 with o + t d on the sphere of `radius` about `centre`, or kNoHit.
double raySphere(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& centre,
                 double radius) {
  const Eigen::Vector3d m = o - centre;
  const double b = m.dot(d), c = m.squaredNorm() - radius * radius;
  const double disc = b * b - c;
  if (disc < 0) return kNoHit;
  const double root = std::sqrt(disc);
  if (-b - root >= 0) return -b - root;
  return -b + root >= 0 ? -b + root : kNoHit;
}

double rayBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& half) {
  double near = 0, far = kNoHit;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-15) {
      if (std::abs(o[a]) > half[a]) return kNoHit;
      continue;
    }
    double t0 = (-half[a] - o[a]) / d[a], t1 = (half[a] - o[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
    if (near > far) return kNoHit;
  }
  return near;
}

/// A ray against the side of the infinite cylinder of `radius` about z, kept where |z| <= half.
double raySide(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double radius, double half) {
  const double a = d.x() * d.x() + d.y() * d.y();
  if (a < 1e-15) return kNoHit;
  const double b = o.x() * d.x() + o.y() * d.y();
  const double c = o.x() * o.x() + o.y() * o.y() - radius * radius;
  const double disc = b * b - a * c;
  if (disc < 0) return kNoHit;
  const double root = std::sqrt(disc);
  for (const double t : {(-b - root) / a, (-b + root) / a}) {
    if (t >= 0 && std::abs(o.z() + t * d.z()) <= half) return t;
  }
  return kNoHit;
}

double rayCylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double radius, double half) {
  if (std::hypot(o.x(), o.y()) <= radius && std::abs(o.z()) <= half) return 0;
  double best = raySide(o, d, radius, half);
  if (std::abs(d.z()) > 1e-15) {
    for (const double z : {-half, half}) {
      const double t = (z - o.z()) / d.z();
      const Eigen::Vector3d p = o + t * d;
      if (t >= 0 && t < best && std::hypot(p.x(), p.y()) <= radius) best = t;
    }
  }
  return best;
}

double rayCapsule(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double radius, double half) {
  double best = raySide(o, d, radius, half);
  for (const double z : {-half, half})
    best = std::min(best, raySphere(o, d, Eigen::Vector3d(0, 0, z), radius));
  return best;
}

/// Möller and Trumbore's ray-triangle test over every triangle.
double rayMesh(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const TriangleMesh& mesh) {
  double best = kNoHit;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d e1 = mesh.vertices[static_cast<std::size_t>(t[1])] - a;
    const Eigen::Vector3d e2 = mesh.vertices[static_cast<std::size_t>(t[2])] - a;
    const Eigen::Vector3d p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-15) continue;
    const Eigen::Vector3d s = o - a;
    const double u = s.dot(p) / det;
    if (u < 0 || u > 1) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (v < 0 || u + v > 1) continue;
    const double hit = e2.dot(q) / det;
    if (hit >= 0 && hit < best) best = hit;
  }
  return best;
}

/// The distance along the ray (o, d) in the shape's frame to its surface, or kNoHit.
double rayShape(const Shape& shape, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  return std::visit(
      Overloaded{
          [&](const Box& b) { return rayBox(o, d, b.size / 2); },
          [&](const Sphere& s) { return raySphere(o, d, Eigen::Vector3d::Zero(), s.radius); },
          [&](const Cylinder& c) { return rayCylinder(o, d, c.radius, c.length / 2); },
          [&](const Capsule& c) { return rayCapsule(o, d, c.radius, c.length / 2); },
          [&](const Mesh& m) { return rayMesh(o, d, *m.mesh); },
          [](const PointCloud&) { return kNoHit; },
      },
      shape);
}

void validateCamera(const DepthCamera& c) {
  if (c.width <= 0 || c.height <= 0)
    throw InvalidArgument("depth camera: " + std::to_string(c.width) + " x " +
                          std::to_string(c.height) + " pixels");
  if (!(c.horizontalFieldOfView > 0 && c.horizontalFieldOfView < std::numbers::pi))
    throw InvalidArgument("depth camera: the field of view must be in (0, pi), got " +
                          std::to_string(c.horizontalFieldOfView));
  if (!(c.minRange >= 0 && c.minRange < c.maxRange && std::isfinite(c.maxRange)))
    throw InvalidArgument("depth camera: the range [" + std::to_string(c.minRange) + ", " +
                          std::to_string(c.maxRange) + "] is empty or not finite");
  if (!(c.depthNoise >= 0 && std::isfinite(c.depthNoise)))
    throw InvalidArgument("depth camera: the depth noise must be finite and >= 0");
}

}  // namespace

Eigen::Isometry3d cameraLookingAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = target - eye;
  if (z.norm() < 1e-12) throw InvalidArgument("cameraLookingAt: the eye is the target");
  const Eigen::Vector3d forward = z.normalized();
  // The image's down is the world's down, made orthogonal to the view.
  Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ());
  if (right.norm() < 1e-9) right = Eigen::Vector3d::UnitX();  // looking straight up or down
  right.normalize();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear().col(0) = right;
  pose.linear().col(1) = forward.cross(right);
  pose.linear().col(2) = forward;
  pose.translation() = eye;
  return pose;
}

CloudPoints renderDepth(const DepthCamera& camera, const Scene& scene, Rng& rng) {
  validateCamera(camera);
  struct Seen {
    const Shape* shape;
    Eigen::Isometry3d toLocal;
    Eigen::Vector3d centre;  // world
    double radius;           // about centre: every point of the shape within
  };
  std::vector<Seen> seen;
  for (const Obstacle& o : scene.obstacles()) {
    if (std::holds_alternative<PointCloud>(o.shape)) continue;
    seen.push_back({&o.shape, o.pose.inverse(), o.pose.translation(), boundingRadius(o.shape)});
  }
  const double focal = camera.width / 2.0 / std::tan(camera.horizontalFieldOfView / 2);
  std::normal_distribution<double> noise(0.0, camera.depthNoise);
  CloudPoints cloud;
  cloud.source = "depth camera";
  const Eigen::Vector3d eye = camera.pose.translation();
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray =
          camera.pose.linear() * Eigen::Vector3d((u + 0.5 - camera.width / 2.0) / focal,
                                                 (v + 0.5 - camera.height / 2.0) / focal, 1)
                                     .normalized();
      double nearest = camera.maxRange;
      bool hit = false;
      for (const Seen& s : seen) {
        if (raySphere(eye, ray, s.centre, s.radius) >= nearest) continue;
        const double t = rayShape(*s.shape, s.toLocal * eye, s.toLocal.linear() * ray);
        if (t >= camera.minRange && t < nearest) {
          nearest = t;
          hit = true;
        }
      }
      if (!hit) continue;
      const double depth = camera.depthNoise > 0 ? nearest + noise(rng) : nearest;
      cloud.points.push_back(eye + depth * ray);
    }
  }
  return cloud;
}

namespace {

void addBoxSurface(const Eigen::Vector3d& size, double spacing, std::vector<Eigen::Vector3d>& out) {
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    const auto na = static_cast<int>(std::ceil(size[a] / spacing));
    const auto nb = static_cast<int>(std::ceil(size[b] / spacing));
    for (const double side : {-0.5, 0.5}) {
      for (int i = 0; i < na; ++i) {
        for (int j = 0; j < nb; ++j) {
          Eigen::Vector3d p;
          p[axis] = side * size[axis];
          p[a] = ((i + 0.5) / na - 0.5) * size[a];
          p[b] = ((j + 0.5) / nb - 0.5) * size[b];
          out.push_back(p);
        }
      }
    }
  }
}

/// Fibonacci points on the sphere of `radius` about `centre`, those with z * keep >= 0 (keep 0:
/// all).
void addSphereSurface(const Eigen::Vector3d& centre, double radius, double spacing, int keep,
                      std::vector<Eigen::Vector3d>& out) {
  const auto n =
      static_cast<int>(std::ceil(4 * std::numbers::pi * radius * radius / (spacing * spacing))) + 1;
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z);
    const Eigen::Vector3d p(r * std::cos(golden * i), r * std::sin(golden * i), z);
    if (keep * p.z() >= 0) out.push_back(centre + radius * p);
  }
}

void addSideSurface(double radius, double length, double spacing,
                    std::vector<Eigen::Vector3d>& out) {
  const auto rings = static_cast<int>(std::ceil(length / spacing)) + 1;
  const auto around = static_cast<int>(std::ceil(2 * std::numbers::pi * radius / spacing));
  for (int i = 0; i < rings; ++i) {
    const double z = rings == 1 ? 0 : (static_cast<double>(i) / (rings - 1) - 0.5) * length;
    for (int k = 0; k < around; ++k) {
      const double angle = 2 * std::numbers::pi * k / around;
      out.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
    }
  }
}

double surfaceArea(const Shape& shape) {
  return std::visit(
      Overloaded{
          [](const Box& b) {
            return 2 *
                   (b.size.x() * b.size.y() + b.size.y() * b.size.z() + b.size.x() * b.size.z());
          },
          [](const Sphere& s) { return 4 * std::numbers::pi * s.radius * s.radius; },
          [](const Cylinder& c) { return 2 * std::numbers::pi * c.radius * (c.radius + c.length); },
          [](const Capsule& c) {
            return 2 * std::numbers::pi * c.radius * (2 * c.radius + c.length);
          },
          [](const Mesh& m) {
            double area = 0;
            for (const auto& t : m.mesh->triangles) {
              const auto& v = m.mesh->vertices;
              area += 0.5 * (v[static_cast<std::size_t>(t[1])] - v[static_cast<std::size_t>(t[0])])
                                .cross(v[static_cast<std::size_t>(t[2])] -
                                       v[static_cast<std::size_t>(t[0])])
                                .norm();
            }
            return area;
          },
          [](const PointCloud&) { return 0.0; },
      },
      shape);
}

}  // namespace

CloudPoints surfacePoints(const Scene& scene, double spacing, Rng& rng) {
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw InvalidArgument("surfacePoints: the spacing must be positive, got " +
                          std::to_string(spacing));
  double area = 0;
  for (const Obstacle& o : scene.obstacles()) area += surfaceArea(o.shape);
  if (area / (spacing * spacing) > static_cast<double>(kMaxSurfacePoints))
    throw InvalidArgument("surfacePoints: a spacing of " + std::to_string(spacing) +
                          " m would need more than 50 million points");
  std::uniform_real_distribution<double> unit(0, 1);
  CloudPoints cloud;
  cloud.source = "surfaces at " + std::to_string(spacing) + " m";
  std::vector<Eigen::Vector3d> local;
  for (const Obstacle& o : scene.obstacles()) {
    local.clear();
    std::visit(Overloaded{
                   [&](const Box& b) { addBoxSurface(b.size, spacing, local); },
                   [&](const Sphere& s) {
                     addSphereSurface(Eigen::Vector3d::Zero(), s.radius, spacing, 0, local);
                   },
                   [&](const Cylinder& c) {
                     addSideSurface(c.radius, c.length, spacing, local);
                     for (double r = c.radius; r > 0; r -= spacing) {  // the caps, ring by ring
                       const auto around =
                           static_cast<int>(std::ceil(2 * std::numbers::pi * r / spacing));
                       for (int k = 0; k < around; ++k) {
                         const double angle = 2 * std::numbers::pi * k / around;
                         for (const double z : {-c.length / 2, c.length / 2})
                           local.emplace_back(r * std::cos(angle), r * std::sin(angle), z);
                       }
                     }
                   },
                   [&](const Capsule& c) {
                     addSideSurface(c.radius, c.length, spacing, local);
                     addSphereSurface({0, 0, c.length / 2}, c.radius, spacing, 1, local);
                     addSphereSurface({0, 0, -c.length / 2}, c.radius, spacing, -1, local);
                   },
                   [&](const Mesh& m) {
                     const auto& v = m.mesh->vertices;
                     for (const auto& t : m.mesh->triangles) {
                       const Eigen::Vector3d& a = v[static_cast<std::size_t>(t[0])];
                       const Eigen::Vector3d e1 = v[static_cast<std::size_t>(t[1])] - a;
                       const Eigen::Vector3d e2 = v[static_cast<std::size_t>(t[2])] - a;
                       const double n = 0.5 * e1.cross(e2).norm() / (spacing * spacing);
                       // A share of a point for small triangles: the density holds on average.
                       auto count = static_cast<int>(n);
                       if (unit(rng) < n - count) ++count;
                       for (int i = 0; i < count; ++i) {
                         double s = unit(rng), w = unit(rng);
                         if (s + w > 1) {
                           s = 1 - s;
                           w = 1 - w;
                         }
                         local.push_back(a + s * e1 + w * e2);
                       }
                     }
                   },
                   [](const PointCloud&) {},
               },
               o.shape);
    for (const Eigen::Vector3d& p : local) cloud.points.push_back(o.pose * p);
  }
  return cloud;
}

}  // namespace fastron
