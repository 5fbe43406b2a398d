#include "fastron/geometry/clearance_bounds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "fastron/core/error.h"
#include "overloaded.h"

namespace fastron {
namespace {

/// A box of `size` centred at the origin cut into at most `maxBalls` equal cells, each covered by
/// the ball through its corners. The longest cell side is halved (the count along it doubled, or
/// grown by one) while the count allows.
std::vector<Ball> gridBalls(const Eigen::Vector3d& size, std::size_t maxBalls) {
  std::array<std::size_t, 3> cells{1, 1, 1};
  for (;;) {
    int longest = 0;
    for (int a = 1; a < 3; ++a) {
      if (size[a] / static_cast<double>(cells[a]) >
          size[longest] / static_cast<double>(cells[longest]))
        longest = a;
    }
    const std::size_t others = cells[0] * cells[1] * cells[2] / cells[longest];
    if ((cells[longest] + 1) * others > maxBalls) break;
    ++cells[longest];
  }
  const Eigen::Vector3d cell(size.x() / static_cast<double>(cells[0]),
                             size.y() / static_cast<double>(cells[1]),
                             size.z() / static_cast<double>(cells[2]));
  std::vector<Ball> balls;
  for (std::size_t i = 0; i < cells[0]; ++i) {
    for (std::size_t j = 0; j < cells[1]; ++j) {
      for (std::size_t k = 0; k < cells[2]; ++k) {
        const Eigen::Vector3d index(static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5,
                                    static_cast<double>(k) + 0.5);
        balls.push_back({(index.cwiseProduct(cell) - size / 2), cell.norm() / 2});
      }
    }
  }
  return balls;
}

/// Slices along z of a solid of `radius` about the z axis and `length` (a cylinder or a
/// capsule's cylinder part), as many as keep a slice no longer than half the radius.
std::size_t sliceCount(double radius, double length, std::size_t maxBalls) {
  const double slices = std::ceil(2 * length / radius);
  return std::clamp<std::size_t>(static_cast<std::size_t>(slices), 1, maxBalls);
}

using Triangle = std::array<Eigen::Vector3d, 3>;

/// The mesh's triangles, each cut in two at the midpoint of its longest edge until no edge is
/// longer than `longest`: long thin triangles (a coarse collision mesh's) would otherwise make any
/// group of triangles that holds one as long as it. Cutting the longest edge only keeps a thin
/// triangle's pieces as few as its length needs (cutting into four made the mesh Panda's covers
/// take 78 ms, most of its checker's start-up).
std::vector<Triangle> pieces(const TriangleMesh& mesh, double longest) {
  std::vector<Triangle> out, todo;
  for (const auto& t : mesh.triangles) {
    todo.push_back({mesh.vertices[static_cast<std::size_t>(t[0])],
                    mesh.vertices[static_cast<std::size_t>(t[1])],
                    mesh.vertices[static_cast<std::size_t>(t[2])]});
  }
  while (!todo.empty()) {
    const Triangle t = todo.back();
    todo.pop_back();
    int edge = 0;  // the edge from corner `edge` to the next
    double length = 0;
    for (int e = 0; e < 3; ++e) {
      const double l =
          (t[static_cast<std::size_t>(e)] - t[static_cast<std::size_t>((e + 1) % 3)]).norm();
      if (l > length) {
        length = l;
        edge = e;
      }
    }
    if (length <= longest) {
      out.push_back(t);
      continue;
    }
    const Eigen::Vector3d& from = t[static_cast<std::size_t>(edge)];
    const Eigen::Vector3d& to = t[static_cast<std::size_t>((edge + 1) % 3)];
    const Eigen::Vector3d& apex = t[static_cast<std::size_t>((edge + 2) % 3)];
    const Eigen::Vector3d middle = (from + to) / 2;
    todo.push_back({from, middle, apex});
    todo.push_back({middle, to, apex});
  }
  return out;
}

/// The ball about the middle of the box around these triangles' corners.
Ball ballAround(const std::vector<Triangle>& triangles, const std::vector<int>& group) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const int t : group) {
    for (const Eigen::Vector3d& v : triangles[static_cast<std::size_t>(t)]) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  }
  Ball ball{(lo + hi) / 2, 0};
  for (const int t : group) {
    for (const Eigen::Vector3d& v : triangles[static_cast<std::size_t>(t)])
      ball.radius = std::max(ball.radius, (v - ball.centre).norm());
  }
  return ball;
}

/// A ball contains a triangle when it contains its corners (both are convex), so groups of
/// triangles, the widest group split in two (across the axis that leaves the smaller balls) until
/// there are maxBalls (or every group is one triangle). Each group's triangles are returned in
/// `groups`.
std::vector<Ball> groupBalls(const std::vector<Triangle>& triangles,
                             const std::vector<Eigen::Vector3d>& centroids, std::vector<int> all,
                             std::size_t maxBalls, std::vector<std::vector<int>>& groups) {
  groups.assign(1, std::move(all));
  std::vector<Ball> balls{ballAround(triangles, groups[0])};
  while (balls.size() < maxBalls) {
    std::size_t widest = balls.size();
    for (std::size_t g = 0; g < balls.size(); ++g) {
      if (groups[g].size() > 1 &&
          (widest == balls.size() || balls[g].radius > balls[widest].radius))
        widest = g;
    }
    if (widest == balls.size()) break;  // every group is one triangle
    std::vector<int>& group = groups[widest];
    Eigen::Vector3d from = centroids[static_cast<std::size_t>(group[0])], to = from;
    for (const int t : group) {
      from = from.cwiseMin(centroids[static_cast<std::size_t>(t)]);
      to = to.cwiseMax(centroids[static_cast<std::size_t>(t)]);
    }
    // Of the cuts across each axis at the middle of the centroids' extent, the one that leaves
    // the larger ball the smallest: a round link is cut into slices, whose balls sit on its axis
    // and hug it, rather than into patches of its surface, which balls about their own middle
    // overhang by about their radius.
    std::vector<int> lower, upper, below, above;
    constexpr double kNone = std::numeric_limits<double>::infinity();
    Ball lowerBall{.radius = kNone}, upperBall{.radius = kNone};  // of the best cut so far
    for (Eigen::Index axis = 0; axis < 3; ++axis) {
      const double cut = (from[axis] + to[axis]) / 2;
      below.clear();
      above.clear();
      for (const int t : group) {
        (centroids[static_cast<std::size_t>(t)][axis] < cut ? below : above).push_back(t);
      }
      if (below.empty() || above.empty()) continue;
      const Ball belowBall = ballAround(triangles, below);
      const Ball aboveBall = ballAround(triangles, above);
      if (std::max(belowBall.radius, aboveBall.radius) <
          std::max(lowerBall.radius, upperBall.radius)) {
        lower.swap(below);
        upper.swap(above);
        lowerBall = belowBall;
        upperBall = aboveBall;
      }
    }
    if (lower.empty()) {  // every centroid in one place: halve the group as it is
      const auto middle = group.begin() + static_cast<std::ptrdiff_t>(group.size() / 2);
      lower.assign(group.begin(), middle);
      upper.assign(middle, group.end());
      lowerBall = ballAround(triangles, lower);
      upperBall = ballAround(triangles, upper);
    }
    group = std::move(lower);
    balls[widest] = lowerBall;
    balls.push_back(upperBall);
    groups.push_back(std::move(upper));
  }
  return balls;
}

/// A point of the mesh near `centre`: the centroid of the group's triangle piece nearest it (a
/// ball of radius 0, inside the shape's surface).
Ball pointNear(const std::vector<Eigen::Vector3d>& centroids, const std::vector<int>& group,
               const Eigen::Vector3d& centre) {
  Ball best{centroids[static_cast<std::size_t>(group.front())], 0};
  for (const int t : group) {
    const Eigen::Vector3d& c = centroids[static_cast<std::size_t>(t)];
    if ((c - centre).squaredNorm() < (best.centre - centre).squaredNorm()) best.centre = c;
  }
  return best;
}

/// The mesh's cover: its triangles cut to at most a twelfth of its size, grouped into maxBalls
/// balls, and each group into up to maxChildren finer ones.
BallCover meshCover(const TriangleMesh& mesh, std::size_t maxBalls, std::size_t maxChildren) {
  Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const std::vector<Triangle> triangles = pieces(mesh, (hi - lo).norm() / 12);
  std::vector<Eigen::Vector3d> centroids;
  for (const Triangle& t : triangles) centroids.push_back((t[0] + t[1] + t[2]) / 3);
  std::vector<int> all(triangles.size());
  std::iota(all.begin(), all.end(), 0);
  BallCover cover;
  std::vector<std::vector<int>> groups, subgroups;
  cover.balls = groupBalls(triangles, centroids, std::move(all), maxBalls, groups);
  if (maxChildren <= 1) {
    for (std::size_t g = 0; g < groups.size(); ++g)
      cover.inside.push_back(pointNear(centroids, groups[g], cover.balls[g].centre));
    return cover;
  }
  for (std::vector<int>& group : groups) {
    cover.children.push_back(
        groupBalls(triangles, centroids, std::move(group), maxChildren, subgroups));
    for (std::size_t g = 0; g < subgroups.size(); ++g)
      cover.inside.push_back(pointNear(centroids, subgroups[g], cover.children.back()[g].centre));
  }
  return cover;
}

/// Balls inside a solid primitive of the robot: the sphere itself; balls of the radius along a
/// capsule's segment or a cylinder's axis; balls of the smallest half-side along a box's longest
/// side, and its corners (balls of radius 0).
std::vector<Ball> solidInside(const Shape& shape) {
  static constexpr std::size_t kMaxBalls = 12;
  // Balls of `radius` centred from -half to half along `axis`, so that neighbours overlap.
  const auto along = [](std::vector<Ball>& out, const Eigen::Vector3d& axis, double half,
                        double radius) {
    const std::size_t n =
        half > 0 && radius > 0
            ? std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(2 * half / radius)) + 1, 2,
                                      kMaxBalls)
            : 1;
    for (std::size_t i = 0; i < n; ++i) {
      const double t = n == 1 ? 0.0 : -half + 2 * half * static_cast<double>(i) / (n - 1.0);
      out.push_back({t * axis, radius});
    }
  };
  std::vector<Ball> out;
  std::visit(
      Overloaded{
          [&](const Box& b) {
            const Eigen::Vector3d half = b.size / 2;
            const double radius = half.minCoeff();
            Eigen::Index longest = 0;
            half.maxCoeff(&longest);
            along(out, Eigen::Vector3d::Unit(longest), half[longest] - radius, radius);
            for (int corner = 0; corner < 8; ++corner) {
              out.push_back({Eigen::Vector3d((corner & 1) != 0 ? half.x() : -half.x(),
                                             (corner & 2) != 0 ? half.y() : -half.y(),
                                             (corner & 4) != 0 ? half.z() : -half.z()),
                             0.0});
            }
          },
          [&](const Sphere& s) {
            out.push_back({Eigen::Vector3d::Zero(), s.radius});
          },
          [&](const Cylinder& c) {
            const double radius = std::min(c.radius, c.length / 2);
            along(out, Eigen::Vector3d::UnitZ(), c.length / 2 - radius, radius);
          },
          [&](const Capsule& c) { along(out, Eigen::Vector3d::UnitZ(), c.length / 2, c.radius); },
          [](const Mesh&) {},
          [](const PointCloud&) {},
      },
      shape);
  return out;
}

}  // namespace

BallCover coveringBallTree(const Shape& shape, std::size_t maxBalls, std::size_t maxChildren) {
  if (maxBalls == 0) throw InvalidArgument("coveringBalls: at least one ball is needed");
  BallCover cover;
  if (const auto* mesh = std::get_if<Mesh>(&shape)) {
    cover = meshCover(*mesh->mesh, maxBalls, maxChildren);
  } else {
    cover.balls = coveringBalls(shape, maxBalls);
    cover.inside = solidInside(shape);
  }
  // About the middle of the box around the balls.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Ball& b : cover.balls) {
    lo = lo.cwiseMin((b.centre.array() - b.radius).matrix());
    hi = hi.cwiseMax((b.centre.array() + b.radius).matrix());
  }
  cover.whole.centre = (lo + hi) / 2;
  for (const Ball& b : cover.balls)
    cover.whole.radius =
        std::max(cover.whole.radius, (b.centre - cover.whole.centre).norm() + b.radius);
  return cover;
}

std::vector<Ball> coveringBalls(const Shape& shape, std::size_t maxBalls) {
  if (maxBalls == 0) throw InvalidArgument("coveringBalls: at least one ball is needed");
  return std::visit(
      Overloaded{
          [&](const Box& b) { return gridBalls(b.size, maxBalls); },
          [](const Sphere& s) {
            return std::vector<Ball>{{Eigen::Vector3d::Zero(), s.radius}};
          },
          [&](const Cylinder& c) {
            const std::size_t n = sliceCount(c.radius, c.length, maxBalls);
            const double slice = c.length / static_cast<double>(n);
            std::vector<Ball> balls;
            for (std::size_t i = 0; i < n; ++i) {
              const double z = -c.length / 2 + (static_cast<double>(i) + 0.5) * slice;
              balls.push_back({Eigen::Vector3d(0, 0, z), std::hypot(c.radius, slice / 2)});
            }
            return balls;
          },
          // Every point lies within radius of the axis segment, whose every point lies within
          // half a slice of a centre.
          [&](const Capsule& c) {
            const std::size_t n = c.length > 0 ? sliceCount(c.radius, c.length, maxBalls) : 1;
            const double slice = c.length / static_cast<double>(n);
            std::vector<Ball> balls;
            for (std::size_t i = 0; i < n; ++i) {
              const double z = -c.length / 2 + (static_cast<double>(i) + 0.5) * slice;
              balls.push_back({Eigen::Vector3d(0, 0, z), c.radius + slice / 2});
            }
            return balls;
          },
          [&](const Mesh& m) { return meshCover(*m.mesh, maxBalls, 0).balls; },
          [](const PointCloud&) -> std::vector<Ball> {
            throw InvalidArgument("coveringBalls: a point cloud is not a robot shape");
          },
      },
      shape);
}

EnclosingVolume::EnclosingVolume(const Shape& shape, const Eigen::Isometry3d& pose)
    : toLocal_(pose.inverse()) {
  std::visit(Overloaded{
                 [&](const Box& b) { halfExtents_ = b.size / 2; },
                 [&](const Sphere& s) {
                   kind_ = Kind::Sphere;
                   radius_ = s.radius;
                 },
                 [&](const Cylinder& c) {
                   kind_ = Kind::Cylinder;
                   radius_ = c.radius;
                   halfLength_ = c.length / 2;
                 },
                 [&](const Capsule& c) {
                   kind_ = Kind::Capsule;
                   radius_ = c.radius;
                   halfLength_ = c.length / 2;
                 },
                 [&](const Mesh& m) {
                   encloses_ = true;
                   Eigen::Vector3d lo = m.mesh->vertices.front(), hi = lo;
                   for (const auto& v : m.mesh->vertices) {
                     lo = lo.cwiseMin(v);
                     hi = hi.cwiseMax(v);
                   }
                   halfExtents_ = (hi - lo) / 2;
                   toLocal_ = Eigen::Translation3d(-(lo + hi) / 2) * toLocal_;
                 },
                 [&](const PointCloud& c) {
                   encloses_ = true;
                   if (c.cloud->points.empty()) {
                     kind_ = Kind::Nothing;
                     return;
                   }
                   Eigen::Vector3d lo = c.cloud->points.front(), hi = lo;
                   for (const auto& p : c.cloud->points) {
                     lo = lo.cwiseMin(p);
                     hi = hi.cwiseMax(p);
                   }
                   halfExtents_ = ((hi - lo) / 2).array() + c.radius;
                   toLocal_ = Eigen::Translation3d(-(lo + hi) / 2) * toLocal_;
                 },
             },
             shape);
}

template <class Use>
double EnclosingVolume::withLocalDistance(const Use& use) const {
  const double hx = halfExtents_.x(), hy = halfExtents_.y(), hz = halfExtents_.z();
  const double radius = radius_, halfLength = halfLength_;
  switch (kind_) {
    case Kind::Box:
      return use([=](double px, double py, double pz) {
        const double dx = std::max(std::abs(px) - hx, 0.0);
        const double dy = std::max(std::abs(py) - hy, 0.0);
        const double dz = std::max(std::abs(pz) - hz, 0.0);
        return std::sqrt(dx * dx + dy * dy + dz * dz);
      });
    case Kind::Sphere:
      return use([=](double px, double py, double pz) {
        return std::max(std::sqrt(px * px + py * py + pz * pz) - radius, 0.0);
      });
    case Kind::Cylinder:
      return use([=](double px, double py, double pz) {
        const double radial = std::max(std::sqrt(px * px + py * py) - radius, 0.0);
        const double axial = std::max(std::abs(pz) - halfLength, 0.0);
        return std::sqrt(radial * radial + axial * axial);
      });
    case Kind::Capsule:
      return use([=](double px, double py, double pz) {
        const double dz = pz - std::clamp(pz, -halfLength, halfLength);
        return std::max(std::sqrt(px * px + py * py + dz * dz) - radius, 0.0);
      });
    case Kind::Nothing:
      break;
  }
  return use([](double, double, double) { return std::numeric_limits<double>::infinity(); });
}

double EnclosingVolume::distanceFrom(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d p = toLocal_ * point;
  return withLocalDistance([&](const auto& distance) { return distance(p.x(), p.y(), p.z()); });
}

void BallColumns::place(const Eigen::Isometry3d& pose, const std::vector<Ball>& balls) {
  const std::size_t n = balls.size();
  x.resize(n);
  y.resize(n);
  z.resize(n);
  radius.resize(n);
  for (std::size_t b = 0; b < n; ++b) {
    const Eigen::Vector3d c = pose * balls[b].centre;
    x[b] = c.x();
    y[b] = c.y();
    z[b] = c.z();
    radius[b] = balls[b].radius;
  }
}

void BallColumns::clear() {
  x.clear();
  y.clear();
  z.clear();
  radius.clear();
}

void BallColumns::push(const Eigen::Vector3d& centre, double r) {
  x.push_back(centre.x());
  y.push_back(centre.y());
  z.push_back(centre.z());
  radius.push_back(r);
}

namespace {

/// Balls per block of a columns bound: each block's figures are computed in one loop that the
/// compiler vectorises, then their smallest taken.
constexpr std::size_t kBlock = 32;

/// The smallest of gap(i) over the balls of `columns`, i in blocks of kBlock: `gap` writes the
/// figures of balls [from, from + n) to out[0..n).
/// Stops after the first block whose smallest is below `enough`.
template <class Gap>
double smallestOver(const BallColumns& columns, const Gap& gap,
                    double enough = -std::numeric_limits<double>::infinity()) {
  double best = std::numeric_limits<double>::infinity();
  std::array<double, kBlock> out;  // written before it is read
  for (std::size_t from = 0; from < columns.size() && !(best < enough); from += kBlock) {
    const std::size_t n = std::min(kBlock, columns.size() - from);
    gap(from, n, out.data());
    for (std::size_t i = 0; i < n; ++i) best = std::min(best, out[i]);
  }
  return best;
}

}  // namespace

double smallestGap(const BallColumns& columns, const Eigen::Vector3d& point, double pointRadius) {
  const double px = point.x(), py = point.y(), pz = point.z();
  return smallestOver(columns, [&](std::size_t from, std::size_t n, double* out) {
    const double *x = columns.x.data() + from, *y = columns.y.data() + from,
                 *z = columns.z.data() + from, *r = columns.radius.data() + from;
    for (std::size_t i = 0; i < n; ++i) {
      const double dx = x[i] - px, dy = y[i] - py, dz = z[i] - pz;
      out[i] = std::sqrt(dx * dx + dy * dy + dz * dz) - r[i] - pointRadius;
    }
  });
}

template <class Figure>
double EnclosingVolume::smallestInFrame(const BallColumns& columns, const Figure& figure,
                                        double enough) const {
  const Eigen::Matrix3d& rotation = toLocal_.linear();
  const Eigen::Vector3d& shift = toLocal_.translation();
  const double r00 = rotation(0, 0), r01 = rotation(0, 1), r02 = rotation(0, 2);
  const double r10 = rotation(1, 0), r11 = rotation(1, 1), r12 = rotation(1, 2);
  const double r20 = rotation(2, 0), r21 = rotation(2, 1), r22 = rotation(2, 2);
  const double t0 = shift.x(), t1 = shift.y(), t2 = shift.z();
  return smallestOver(
      columns,
      [&](std::size_t from, std::size_t n, double* out) {
        const double *x = columns.x.data() + from, *y = columns.y.data() + from,
                     *z = columns.z.data() + from, *r = columns.radius.data() + from;
        for (std::size_t i = 0; i < n; ++i) {
          out[i] = figure(r00 * x[i] + r01 * y[i] + r02 * z[i] + t0,
                          r10 * x[i] + r11 * y[i] + r12 * z[i] + t1,
                          r20 * x[i] + r21 * y[i] + r22 * z[i] + t2) -
                   r[i];
        }
      },
      enough);
}

double EnclosingVolume::smallestGap(const BallColumns& columns) const {
  // One loop per kind of volume, its distance inlined, so that each runs in vector lanes.
  return withLocalDistance([&](const auto& distance) {
    return smallestInFrame(columns, distance, -std::numeric_limits<double>::infinity());
  });
}

bool EnclosingVolume::reachedBy(const BallColumns& columns, double depth) const {
  if (encloses_ || kind_ == Kind::Nothing) return false;
  // One loop per kind of volume, its signed distance (negative inside) inlined, so that each
  // runs in vector lanes; a block that reaches deep enough ends the search.
  const auto reached = [&](const auto& signedDistance) {
    return smallestInFrame(columns, signedDistance, -depth) < -depth;
  };
  const double hx = halfExtents_.x(), hy = halfExtents_.y(), hz = halfExtents_.z();
  const double radius = radius_, halfLength = halfLength_;
  switch (kind_) {
    case Kind::Box:
      return reached([=](double px, double py, double pz) {
        const double qx = std::abs(px) - hx, qy = std::abs(py) - hy, qz = std::abs(pz) - hz;
        const double ox = std::max(qx, 0.0), oy = std::max(qy, 0.0), oz = std::max(qz, 0.0);
        return std::sqrt(ox * ox + oy * oy + oz * oz) +
               std::min(std::max(qx, std::max(qy, qz)), 0.0);
      });
    case Kind::Sphere:
      return reached([=](double px, double py, double pz) {
        return std::sqrt(px * px + py * py + pz * pz) - radius;
      });
    case Kind::Cylinder:
      return reached([=](double px, double py, double pz) {
        const double radial = std::sqrt(px * px + py * py) - radius;
        const double axial = std::abs(pz) - halfLength;
        const double outRadial = std::max(radial, 0.0), outAxial = std::max(axial, 0.0);
        return std::sqrt(outRadial * outRadial + outAxial * outAxial) +
               std::min(std::max(radial, axial), 0.0);
      });
    case Kind::Capsule:
      return reached([=](double px, double py, double pz) {
        const double dz = pz - std::clamp(pz, -halfLength, halfLength);
        return std::sqrt(px * px + py * py + dz * dz) - radius;
      });
    case Kind::Nothing:
      break;
  }
  return false;
}

int commonAncestor(const Robot& robot, int linkA, int linkB) {
  const auto parentLink = [&](int link) {
    const int joint = robot.links()[static_cast<std::size_t>(link)].parentJoint;
    return joint < 0 ? -1 : robot.joints()[static_cast<std::size_t>(joint)].parent;
  };
  std::vector<int> ancestorsOfA;
  for (int link = linkA; link >= 0; link = parentLink(link)) ancestorsOfA.push_back(link);
  for (int link = linkB; link >= 0; link = parentLink(link)) {
    if (std::find(ancestorsOfA.begin(), ancestorsOfA.end(), link) != ancestorsOfA.end())
      return link;
  }
  return robot.rootLink();  // one tree: not reached
}

namespace {

struct LeversAndReach {
  Eigen::VectorXd levers;
  double reach = 0;  ///< bound on any point's distance from relativeTo's origin
  std::vector<ShapeMover> movers;
};

LeversAndReach leversAndReach(const Robot& robot, std::size_t shape, const std::vector<Ball>& balls,
                              int relativeTo) {
  const LinkShape& s = robot.shapes().at(shape);
  const auto& joints = robot.joints();
  // The coordinate that drives each joint, with the multiplier it is driven by.
  std::vector<std::pair<int, double>> driver(joints.size(), {-1, 0.0});
  for (std::size_t k = 0; k < robot.actuatedJoints().size(); ++k)
    driver[static_cast<std::size_t>(robot.actuatedJoints()[k])] = {static_cast<int>(k), 1.0};
  for (const MimicJoint& m : robot.mimicJoints()) {
    const auto& source = driver[static_cast<std::size_t>(m.source)];
    if (source.first >= 0) driver[static_cast<std::size_t>(m.joint)] = {source.first, m.multiplier};
  }
  // The largest distance of a point of the shape from the origin of the current link's frame,
  // carried up the chain: a revolute joint's axis passes through its child link's origin.
  double reach = 0;
  for (const Ball& b : balls) reach = std::max(reach, (s.origin * b.centre).norm() + b.radius);
  Eigen::VectorXd levers = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(robot.dof()));
  std::vector<ShapeMover> movers;
  for (int link = s.link; link != relativeTo;) {
    const int j = robot.links()[static_cast<std::size_t>(link)].parentJoint;
    if (j < 0) {
      throw InvalidArgument("shapeLevers: link '" +
                            robot.links()[static_cast<std::size_t>(relativeTo)].name +
                            "' is not an ancestor of link '" +
                            robot.links()[static_cast<std::size_t>(s.link)].name + "'");
    }
    const Joint& joint = joints[static_cast<std::size_t>(j)];
    const auto [coordinate, multiplier] = driver[static_cast<std::size_t>(j)];
    if (coordinate >= 0 && joint.movable()) {
      // The levers so far are those of the joints below this one.
      movers.push_back({j, static_cast<std::size_t>(coordinate), std::abs(multiplier),
                        joint.type == JointType::Prismatic, levers});
      levers[coordinate] +=
          std::abs(multiplier) * (joint.type == JointType::Prismatic ? 1.0 : reach);
    }
    reach += joint.origin.translation().norm();
    if (joint.type == JointType::Prismatic) {
      double travel = std::max(std::abs(joint.lower), std::abs(joint.upper));
      if (joint.mimic) {  // the followed joint's range, not the mimic's own limits
        for (const MimicJoint& m : robot.mimicJoints()) {
          if (m.joint != j) continue;
          const Joint& source = joints[static_cast<std::size_t>(m.source)];
          travel =
              std::abs(m.multiplier) * std::max(std::abs(source.lower), std::abs(source.upper)) +
              std::abs(m.offset);
        }
      }
      reach += travel;
    }
    link = joint.parent;
  }
  return {levers, reach, std::move(movers)};
}

}  // namespace

Eigen::VectorXd shapeLevers(const Robot& robot, std::size_t shape, const std::vector<Ball>& balls,
                            int relativeTo) {
  return leversAndReach(robot, shape, balls, relativeTo).levers;
}

std::vector<ShapeMover> shapeMovers(const Robot& robot, std::size_t shape,
                                    const std::vector<Ball>& balls, int relativeTo) {
  return leversAndReach(robot, shape, balls, relativeTo).movers;
}

double reachBound(const Robot& robot, double padding) {
  double reach = 0;
  for (std::size_t s = 0; s < robot.shapes().size(); ++s) {
    const std::vector<Ball> whole{
        {Eigen::Vector3d::Zero(), boundingRadius(robot.shapes()[s].shape) + padding}};
    reach = std::max(reach, leversAndReach(robot, s, whole, robot.rootLink()).reach);
  }
  return reach;
}

}  // namespace fastron
