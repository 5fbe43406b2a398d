// Clearance bounds and the motion check they certify: balls cover their shapes, enclosing volumes
// bound distances from below, levers bound how far shapes move, and FclChecker's certified
// motion check answers as the dense check on thousands of seeded motions near obstacles, on every
// shipped robot, with self-collision.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/motion_states.h"
#include "fastron/geometry/certified_motion.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene.h"

namespace fastron {
namespace {

#ifdef FASTRON_SANITIZED
constexpr std::size_t kMotions = 100;  // sanitizers slow checks down ~10 times
#else
constexpr std::size_t kMotions = 300;
#endif

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;  // clang 14 does not deduce aggregates' arguments

bool covered(const std::vector<Ball>& balls, const Eigen::Vector3d& p) {
  for (const Ball& b : balls) {
    if ((p - b.centre).norm() <= b.radius + 1e-12) return true;
  }
  return false;
}

/// Points of the shape: its solid for a primitive, its triangles for a mesh.
std::vector<Eigen::Vector3d> pointsOf(const Shape& shape, std::size_t n, Rng& rng) {
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  std::vector<Eigen::Vector3d> points;
  while (points.size() < n) {
    const Eigen::Vector3d u(sym(rng), sym(rng), sym(rng));
    std::visit(
        Overloaded{
            [&](const Box& b) { points.push_back(u.cwiseProduct(b.size) / 2); },
            [&](const Sphere& s) {
              if (u.norm() <= 1) points.push_back(u * s.radius);
            },
            [&](const Cylinder& c) {
              if (u.head<2>().norm() <= 1)
                points.emplace_back(u.x() * c.radius, u.y() * c.radius, u.z() * c.length / 2);
            },
            [&](const Capsule& c) {
              const Eigen::Vector3d p = u * (c.radius + c.length / 2);
              const double z = std::clamp(p.z(), -c.length / 2, c.length / 2);
              if ((p - Eigen::Vector3d(0, 0, z)).norm() <= c.radius) points.push_back(p);
            },
            [&](const Mesh& m) {
              const auto& t = m.mesh->triangles[static_cast<std::size_t>(
                  unit(rng) * static_cast<double>(m.mesh->triangles.size() - 1))];
              double a = unit(rng), b = unit(rng);
              if (a + b > 1) {
                a = 1 - a;
                b = 1 - b;
              }
              const auto& v = m.mesh->vertices;
              points.push_back(
                  v[static_cast<std::size_t>(t[0])] +
                  a * (v[static_cast<std::size_t>(t[1])] - v[static_cast<std::size_t>(t[0])]) +
                  b * (v[static_cast<std::size_t>(t[2])] - v[static_cast<std::size_t>(t[0])]));
            },
            [&](const PointCloud& c) {
              const auto& p = c.cloud->points;
              points.push_back(
                  p[static_cast<std::size_t>(unit(rng) * static_cast<double>(p.size() - 1))]);
            },
        },
        shape);
  }
  return points;
}

TEST(CoveringBalls, EveryPointOfEveryShapeLiesInABall) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{0, 0, 0}, {0.4, 0, 0}, {0, 0.1, 0}, {0, 0, 0.05}, {0.4, 0.1, 0.05}};
  mesh->triangles = {{0, 1, 2}, {0, 1, 3}, {1, 2, 4}, {0, 2, 3}, {1, 3, 4}};
  const std::vector<Shape> shapes{Box{{0.6, 0.1, 0.02}}, Sphere{0.07},    Cylinder{0.05, 0.4},
                                  Capsule{0.04, 0.3},    Capsule{0.1, 0}, Mesh{mesh}};
  Rng rng(7);
  for (const Shape& shape : shapes) {
    for (const std::size_t count : {1, 3, 12}) {
      const std::vector<Ball> balls = coveringBalls(shape, count);
      ASSERT_FALSE(balls.empty());
      EXPECT_LE(balls.size(), count) << describe(shape);
      for (const Eigen::Vector3d& p : pointsOf(shape, 2000, rng))
        ASSERT_TRUE(covered(balls, p)) << describe(shape) << " with " << count << " balls";
    }
  }
  // Cut along its length, a long cylinder is hugged: no ball much wider than it.
  for (const Ball& b : coveringBalls(Cylinder{0.05, 0.4}, 12)) EXPECT_LT(b.radius, 0.06);
  EXPECT_THROW(coveringBalls(Sphere{1}, 0), InvalidArgument);
}

// A link's mesh as collision meshes often are: a closed tube (radius 4 cm, 40 cm long) of rings
// of long, thin triangles, capped by fans.
Shape tubeMesh() {
  constexpr int kSides = 24, kRings = 3;
  constexpr double kRadius = 0.04, kLength = 0.4;
  auto mesh = std::make_shared<TriangleMesh>();
  for (int r = 0; r < kRings; ++r) {
    for (int k = 0; k < kSides; ++k) {
      const double a = 2 * std::numbers::pi * k / kSides;
      mesh->vertices.emplace_back(kRadius * std::cos(a), kRadius * std::sin(a),
                                  kLength * r / (kRings - 1));
    }
  }
  mesh->vertices.emplace_back(0, 0, 0);
  mesh->vertices.emplace_back(0, 0, kLength);
  const int bottom = kRings * kSides, top = bottom + 1;
  for (int k = 0; k < kSides; ++k) {
    const int next = (k + 1) % kSides;
    for (int r = 0; r + 1 < kRings; ++r) {
      mesh->triangles.push_back({r * kSides + k, r * kSides + next, (r + 1) * kSides + next});
      mesh->triangles.push_back({r * kSides + k, (r + 1) * kSides + next, (r + 1) * kSides + k});
    }
    mesh->triangles.push_back({bottom, next, k});
    mesh->triangles.push_back({top, (kRings - 1) * kSides + k, (kRings - 1) * kSides + next});
  }
  return Mesh{mesh};
}

TEST(CoveringBalls, ATubeOfMeshIsCutIntoSlicesOnItsAxis) {
  const Shape tube = tubeMesh();
  const BallCover cover = coveringBallTree(tube, 12, 8);
  ASSERT_EQ(cover.balls.size(), 12u);
  ASSERT_EQ(cover.children.size(), 12u);
  // Slices about the axis, not patches of the surface: a patch's ball overhangs the tube by
  // about its own radius (the median cut made balls of 5.6 to 7.5 cm on such a link).
  for (const Ball& b : cover.balls) {
    EXPECT_LT(b.radius, 0.048) << b.centre.transpose();
    EXPECT_LT(b.centre.head<2>().norm(), 0.005) << b.centre.transpose();
  }
  // Every point of the tube lies in a ball, and in a child of a ball that holds it.
  Rng rng(3);
  for (const Eigen::Vector3d& p : pointsOf(tube, 4000, rng)) {
    bool inChild = false;
    for (std::size_t b = 0; b < cover.balls.size(); ++b) {
      if (covered({cover.balls[b]}, p)) inChild = inChild || covered(cover.children[b], p);
    }
    ASSERT_TRUE(covered(cover.balls, p)) << p.transpose();
    ASSERT_TRUE(inChild) << p.transpose();
  }
}

/// Whether p lies on one of the mesh's triangles (within 1e-9 m of its plane, inside its edges).
bool onTriangles(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d u = mesh.vertices[static_cast<std::size_t>(t[1])] - a;
    const Eigen::Vector3d v = mesh.vertices[static_cast<std::size_t>(t[2])] - a;
    const Eigen::Vector3d n = u.cross(v);
    if (std::abs(n.normalized().dot(p - a)) > 1e-9) continue;
    // Barycentric coordinates of p in (a, u, v).
    const double su = (p - a).cross(v).dot(n) / n.squaredNorm();
    const double sv = u.cross(p - a).dot(n) / n.squaredNorm();
    if (su >= -1e-9 && sv >= -1e-9 && su + sv <= 1 + 1e-9) return true;
  }
  return false;
}

// The cover's dual: balls inside each shape. A solid primitive's lie in its solid; a mesh's are
// points of its triangles, one per finest ball of its cover.
TEST(InsideBalls, LieInsideTheirShape) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{0, 0, 0}, {0.4, 0, 0}, {0, 0.1, 0}, {0, 0, 0.05}, {0.4, 0.1, 0.05}};
  mesh->triangles = {{0, 1, 2}, {0, 1, 3}, {1, 2, 4}, {0, 2, 3}, {1, 3, 4}};
  const std::vector<Shape> shapes{
      Box{{0.6, 0.1, 0.02}}, Sphere{0.07},    Cylinder{0.05, 0.4}, Cylinder{0.3, 0.02},
      Capsule{0.04, 0.3},    Capsule{0.1, 0}, Mesh{mesh},          tubeMesh()};
  Rng rng(17);
  std::uniform_real_distribution<double> sym(-1, 1);
  for (const Shape& shape : shapes) {
    const BallCover cover = coveringBallTree(shape, 12, 8);
    ASSERT_FALSE(cover.inside.empty()) << describe(shape);
    if (const auto* m = std::get_if<Mesh>(&shape)) {
      std::size_t finest = 0;
      for (const auto& children : cover.children) finest += children.size();
      EXPECT_EQ(cover.inside.size(), finest) << describe(shape);
      for (const Ball& b : cover.inside) {
        EXPECT_EQ(b.radius, 0) << describe(shape);
        EXPECT_TRUE(onTriangles(*m->mesh, b.centre)) << describe(shape) << b.centre.transpose();
      }
      continue;
    }
    const EnclosingVolume solid(shape, Eigen::Isometry3d::Identity());
    for (const Ball& b : cover.inside) {
      EXPECT_LE(solid.distanceFrom(b.centre), 1e-12) << describe(shape);
      for (int i = 0; i < 200; ++i) {
        const Eigen::Vector3d u(sym(rng), sym(rng), sym(rng));
        if (u.norm() > 1) continue;
        EXPECT_LE(solid.distanceFrom(b.centre + b.radius * u), 1e-12) << describe(shape);
      }
    }
  }
  // A box's corners are among its balls: a corner in an obstacle is a touch.
  const BallCover box = coveringBallTree(Box{{0.6, 0.1, 0.02}});
  EXPECT_EQ(std::count_if(box.inside.begin(), box.inside.end(),
                          [](const Ball& b) {
                            return b.radius == 0 && std::abs(b.centre.x()) == 0.3 &&
                                   std::abs(b.centre.y()) == 0.05 && std::abs(b.centre.z()) == 0.01;
                          }),
            8);
}

TEST(EnclosingVolume, ABallReachesInWhereItOverlapsTheSolidByMoreThanTheDepth) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh->triangles = {{0, 1, 2}};
  auto cloud = std::make_shared<CloudPoints>();
  cloud->points = {{0, 0, 0}, {0.2, 0, 0}};
  const Eigen::Isometry3d pose = Eigen::Translation3d(0.3, -0.2, 0.5) *
                                 Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  constexpr double kDepth = 1e-4;
  const auto one = [](const Eigen::Vector3d& centre, double radius) {
    BallColumns columns;
    columns.push(centre, radius);
    return columns;
  };
  Rng rng(19);
  std::uniform_real_distribution<double> sym(-1, 1), radius(0, 0.2);
  for (const Shape& shape : std::vector<Shape>{Box{{0.4, 0.2, 0.1}}, Sphere{0.3},
                                               Cylinder{0.2, 0.6}, Capsule{0.1, 0.5}}) {
    const EnclosingVolume volume(shape, pose);
    int reached = 0;
    for (int i = 0; i < 3000; ++i) {
      const Eigen::Vector3d centre = pose * Eigen::Vector3d(sym(rng), sym(rng), sym(rng)) / 2;
      const double r = radius(rng);
      const double outside = volume.distanceFrom(centre);
      const bool reaches = volume.reachedBy(one(centre, r), kDepth);
      reached += reaches ? 1 : 0;
      // Outside, it reaches in where it overlaps the solid by more than the depth (distances
      // from primitives are exact: DistancesAreExactForPrimitivesAndBelowForMeshes); inside, a
      // ball larger than the depth always does.
      if (outside > 0) {
        EXPECT_EQ(reaches, outside - r < -kDepth) << describe(shape) << " " << outside - r;
      } else if (r > kDepth) {
        EXPECT_TRUE(reaches) << describe(shape);
      }
    }
    EXPECT_GT(reached, 150) << describe(shape);
  }
  // Points (balls of radius 0) just inside a face: twice the depth in reaches, half of it does
  // not.
  const Box box{{0.4, 0.2, 0.1}};
  const EnclosingVolume boxVolume(box, pose);
  EXPECT_TRUE(boxVolume.reachedBy(one(pose * Eigen::Vector3d(0.2 - 2 * kDepth, 0, 0), 0), kDepth));
  EXPECT_FALSE(boxVolume.reachedBy(one(pose * Eigen::Vector3d(0.2 - kDepth / 2, 0, 0), 0), kDepth));
  EXPECT_FALSE(boxVolume.reachedBy(one(pose * Eigen::Vector3d(0.2 - 2 * kDepth, 0.1, 0), 0),
                                   kDepth));  // on an edge: no deeper than the other face
  const EnclosingVolume sphere(Sphere{0.3}, pose);
  EXPECT_TRUE(sphere.reachedBy(one(pose * Eigen::Vector3d(0, 0.3 - 2 * kDepth, 0), 0), kDepth));
  EXPECT_FALSE(sphere.reachedBy(one(pose * Eigen::Vector3d(0, 0.3 - kDepth / 2, 0), 0), kDepth));
  const EnclosingVolume cylinder(Cylinder{0.2, 0.6}, pose);
  EXPECT_TRUE(cylinder.reachedBy(one(pose * Eigen::Vector3d(0, 0, 0.3 - 2 * kDepth), 0), kDepth));
  EXPECT_FALSE(cylinder.reachedBy(one(pose * Eigen::Vector3d(0, 0, 0.3 - kDepth / 2), 0), kDepth));
  EXPECT_TRUE(cylinder.reachedBy(one(pose * Eigen::Vector3d(0.2 - 2 * kDepth, 0, 0), 0), kDepth));
  const EnclosingVolume capsule(Capsule{0.1, 0.5}, pose);
  EXPECT_TRUE(capsule.reachedBy(one(pose * Eigen::Vector3d(0, 0, 0.35 - 2 * kDepth), 0), kDepth));
  EXPECT_FALSE(capsule.reachedBy(one(pose * Eigen::Vector3d(0, 0, 0.35 - kDepth / 2), 0), kDepth));
  // Of many balls, one reaching in is enough, in any block of the columns; none, none.
  BallColumns many;
  for (int i = 0; i < 75; ++i) many.push(pose * Eigen::Vector3d(2 + i, 0, 0), 0.1);
  EXPECT_FALSE(boxVolume.reachedBy(many, kDepth));
  many.push(pose * Eigen::Vector3d(0, 0, 0), 0);
  EXPECT_TRUE(boxVolume.reachedBy(many, kDepth));
  // A volume around its obstacle proves nothing: a mesh's box, a cloud's.
  EXPECT_FALSE(EnclosingVolume(Mesh{mesh}, pose).reachedBy(many, kDepth));
  EXPECT_FALSE(EnclosingVolume(PointCloud{cloud, 0.05}, pose).reachedBy(many, kDepth));
}

TEST(EnclosingVolume, DistancesAreExactForPrimitivesAndBelowForMeshes) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh->triangles = {{0, 1, 2}};
  const Eigen::Isometry3d pose = Eigen::Translation3d(0.3, -0.2, 0.5) *
                                 Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  Rng rng(3);
  std::uniform_real_distribution<double> sym(-2, 2);
  for (const Shape& shape : std::vector<Shape>{Box{{0.4, 0.2, 0.1}}, Sphere{0.3},
                                               Cylinder{0.2, 0.6}, Capsule{0.1, 0.5}, Mesh{mesh}}) {
    const EnclosingVolume volume(shape, pose);
    const std::vector<Eigen::Vector3d> inside = pointsOf(shape, 3000, rng);
    for (const Eigen::Vector3d& p : inside) EXPECT_NEAR(volume.distanceFrom(pose * p), 0, 1e-12);
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d query(sym(rng), sym(rng), sym(rng));
      double nearest = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& p : inside)
        nearest = std::min(nearest, (pose * p - query).norm());
      const double bound = volume.distanceFrom(query);
      EXPECT_LE(bound, nearest + 1e-12) << describe(shape);
      // Exact for a primitive: the sampled solid comes within a few centimetres of its surface.
      if (!std::holds_alternative<Mesh>(shape)) {
        EXPECT_GT(bound, nearest - 0.05) << describe(shape);
      }
    }
  }
}

TEST(EnclosingVolume, SmallestGapOverColumnsIsTheSmallestBallByBall) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh->triangles = {{0, 1, 2}};
  auto cloud = std::make_shared<CloudPoints>();
  const Eigen::Isometry3d pose = Eigen::Translation3d(0.3, -0.2, 0.5) *
                                 Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  Rng rng(5);
  std::uniform_real_distribution<double> sym(-2, 2), radius(0, 0.3);
  // 1 ball, one block of columns, and blocks after the first (a partial one last).
  for (const std::size_t count : {1, 7, 32, 75}) {
    std::vector<Ball> balls(count);
    for (Ball& b : balls) b = {{sym(rng), sym(rng), sym(rng)}, radius(rng)};
    const Eigen::Isometry3d placed =
        Eigen::Translation3d(0.1, 0.2, -0.3) * Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitY());
    BallColumns columns;
    columns.place(placed, balls);
    ASSERT_EQ(columns.size(), count);
    for (const Shape& shape :
         std::vector<Shape>{Box{{0.4, 0.2, 0.1}}, Sphere{0.3}, Cylinder{0.2, 0.6},
                            Capsule{0.1, 0.5}, Mesh{mesh}, PointCloud{cloud, 0.01}}) {
      const EnclosingVolume volume(shape, pose);
      double smallest = std::numeric_limits<double>::infinity();
      for (const Ball& b : balls)
        smallest = std::min(smallest, volume.distanceFrom(placed * b.centre) - b.radius);
      if (std::isinf(smallest)) {  // the empty cloud: nothing to be near
        EXPECT_TRUE(std::isinf(volume.smallestGap(columns)));
      } else {
        EXPECT_NEAR(volume.smallestGap(columns), smallest, 1e-12) << describe(shape) << count;
      }
    }
    const Eigen::Vector3d point(sym(rng), sym(rng), sym(rng));
    double nearest = std::numeric_limits<double>::infinity();
    for (const Ball& b : balls)
      nearest = std::min(nearest, (placed * b.centre - point).norm() - b.radius - 0.05);
    EXPECT_NEAR(smallestGap(columns, point, 0.05), nearest, 1e-12) << count;
  }
}

Joint joint(const std::string& name, JointType type, int parent, const Eigen::Vector3d& offset,
            const Eigen::Vector3d& axis, double lower, double upper) {
  Joint j;
  j.name = name;
  j.type = type;
  j.parent = parent;
  j.child = parent + 1;
  j.origin = Eigen::Translation3d(offset) * Eigen::Isometry3d::Identity();
  j.axis = axis;
  j.lower = lower;
  j.upper = upper;
  return j;
}

/// A prismatic joint, a revolute one, and a finger that mimics the revolute joint at -2 times its
/// angle: levers of every kind of joint.
Robot slider() {
  const Joint lift = joint("lift", JointType::Prismatic, 0, Eigen::Vector3d::Zero(),
                           Eigen::Vector3d::UnitZ(), -0.2, 0.5);
  const Joint turn =
      joint("turn", JointType::Revolute, 1, {0, 0, 0.3}, Eigen::Vector3d::UnitZ(), -2, 2);
  Joint finger =
      joint("finger", JointType::Revolute, 2, {0.4, 0, 0}, Eigen::Vector3d::UnitY(), -4, 4);
  finger.mimic = Mimic{"turn", -2, 0.1};
  const auto box = [](int link, double x) {
    return LinkShape{link, Eigen::Isometry3d(Eigen::Translation3d(x, 0, 0)),
                     Box{{0.2, 0.05, 0.05}}};
  };
  return Robot("slider", {{"base"}, {"carriage"}, {"arm"}, {"tip"}}, {lift, turn, finger},
               {box(0, 0.3), box(1, 0), box(2, 0.2), box(3, 0.1)});
}

/// How far the farthest moving of `points` (in shape s's frame) moves, relative to link
/// `relativeTo`, from configuration q0 to q1 (a and b: scratch kinematics).
double farthestMove(const Robot& robot, std::size_t s, const std::vector<Eigen::Vector3d>& points,
                    int relativeTo, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                    KinematicsData& a, KinematicsData& b) {
  forwardKinematics(robot, q0.data(), a);
  forwardKinematics(robot, q1.data(), b);
  const auto in = [&](const KinematicsData& k, const Eigen::Vector3d& p) {
    const Eigen::Isometry3d frame = k.linkPoses[static_cast<std::size_t>(relativeTo)];
    return Eigen::Vector3d(frame.inverse() * shapePose(robot, k, s) * p);
  };
  double moved = 0;
  for (const Eigen::Vector3d& p : points) moved = std::max(moved, (in(b, p) - in(a, p)).norm());
  return moved;
}

/// Between pairs of uniform configurations, no sampled point of any shape moves, relative to the
/// root or to its own link, further than its levers allow.
void expectLeversHold(const Robot& robot, Rng& rng, int samples) {
  const JointLimits limits = robot.limits();
  const Configurations starts =
      uniformConfigurations(limits, static_cast<std::size_t>(samples), rng);
  const Configurations ends = uniformConfigurations(limits, static_cast<std::size_t>(samples), rng);
  KinematicsData a = makeKinematicsData(robot), b = makeKinematicsData(robot);
  for (std::size_t s = 0; s < robot.shapes().size(); ++s) {
    const std::vector<Ball> balls = coveringBalls(robot.shapes()[s].shape);
    const std::vector<Eigen::Vector3d> points = pointsOf(robot.shapes()[s].shape, 40, rng);
    for (const int relativeTo : {robot.rootLink(), robot.shapes()[s].link}) {
      const Eigen::VectorXd levers = shapeLevers(robot, s, balls, relativeTo);
      for (int i = 0; i < samples; ++i) {
        const Eigen::VectorXd q0 = starts.row(i).transpose(), q1 = ends.row(i).transpose();
        const double moved = farthestMove(robot, s, points, relativeTo, q0, q1, a, b);
        ASSERT_LE(moved, levers.dot((q1 - q0).cwiseAbs()) + 1e-9)
            << robot.name() << " shape " << s << " relative to link " << relativeTo;
      }
    }
  }
}

/// A configuration in a uniformly random direction from `from`, a length drawn in [shortest,
/// longest) away before it is held within the limits.
Eigen::VectorXd motionEnd(const Eigen::VectorXd& from, const JointLimits& limits, double shortest,
                          double longest, Rng& rng) {
  std::normal_distribution<double> gauss;
  Eigen::VectorXd direction(from.size());
  for (auto& v : direction) v = gauss(rng);
  const double length = std::uniform_real_distribution<double>(shortest, longest)(rng);
  return (from + length * direction.normalized()).cwiseMax(limits.lower()).cwiseMin(limits.upper());
}

/// Whether a dense check of the motion's `n` states (from excluded) finds one colliding.
bool denseMotionCollides(const FclChecker& dense, const Eigen::VectorXd& from,
                         const Eigen::VectorXd& to, std::size_t n) {
  std::vector<double> all;
  motionStates(from.data(), to.data(), dense.dof(), n, all);
  return dense.firstInCollision(all.data(), n) < n;
}

/// Near a configuration, no sampled point of a shape moves in a step, relative to the root or to
/// an ancestor two joints up, further than its speed there (PlacedBalls::speed) grown by its
/// movers' growth for each step away; the movers relative to an ancestor are the first of those
/// relative to the root.
void expectSpeedsHold(const Robot& robot, Rng& rng, int samples) {
  const std::size_t dim = robot.dof();
  const std::size_t shapes = robot.shapes().size();
  auto covers = std::make_shared<std::vector<BallCover>>();
  std::vector<std::vector<ShapeMover>> movers;
  for (std::size_t s = 0; s < shapes; ++s) {
    covers->push_back(coveringBallTree(robot.shapes()[s].shape));
    movers.push_back(shapeMovers(robot, s, {covers->back().whole}, robot.rootLink()));
  }
  KinematicsData placed = makeKinematicsData(robot);
  ExactPairCheck exact;  // as FclChecker places the robot
  exact.place = [&](const double* q, std::vector<Eigen::Isometry3d>& poses) {
    forwardKinematics(robot, q, placed);
    poses.resize(shapes);
    for (std::size_t s = 0; s < shapes; ++s) poses[s] = shapePose(robot, placed, s);
  };
  exact.axes = [&](std::vector<JointAxis>& axes) {
    axes.resize(robot.joints().size());
    for (std::size_t j = 0; j < robot.joints().size(); ++j) {
      const Joint& joint = robot.joints()[j];
      const Eigen::Isometry3d& child = placed.linkPoses[static_cast<std::size_t>(joint.child)];
      axes[j] = {child.translation(), child.linear() * joint.axis};
    }
  };
  PlacedBalls balls(covers);
  const auto parentLink = [&](int link) {
    const int joint = robot.links()[static_cast<std::size_t>(link)].parentJoint;
    return joint < 0 ? link : robot.joints()[static_cast<std::size_t>(joint)].parent;
  };
  constexpr int kSteps = 8;
  KinematicsData a = makeKinematicsData(robot), b = makeKinematicsData(robot);
  const std::vector<std::uint8_t> moves = shapesMovedByConfiguration(robot);
  for (std::size_t s = 0; s < shapes; ++s) {
    if (moves[s] == 0) continue;
    const std::vector<Eigen::Vector3d> points = pointsOf(robot.shapes()[s].shape, 20, rng);
    const int link = robot.shapes()[s].link;
    for (const int relativeTo : {robot.rootLink(), parentLink(parentLink(link))}) {
      const std::vector<ShapeMover> mine = shapeMovers(robot, s, {(*covers)[s].whole}, relativeTo);
      ASSERT_LE(mine.size(), movers[s].size());
      for (std::size_t m = 0; m < mine.size(); ++m) ASSERT_EQ(mine[m].joint, movers[s][m].joint);
      ClearancePair pair;
      pair.shape = s;
      pair.shapeMovers = static_cast<std::uint32_t>(mine.size());
      for (int i = 0; i < samples; ++i) {
        const Eigen::VectorXd q0 = uniformConfigurations(robot.limits(), 1, rng).row(0).transpose();
        // Within the limits: the levers below count prismatic joints' ranges.
        const Eigen::VectorXd end = motionEnd(q0, robot.limits(), 0.5, 4.0, rng);
        const Eigen::VectorXd step = (end - q0) / kSteps;
        const Eigen::VectorXd absStep = step.cwiseAbs();
        const std::vector<double> stride(absStep.data(), absStep.data() + dim);
        balls.place(exact, q0.data());
        const double speed = balls.speed(exact, pair, movers, stride);
        double growth = 0;
        for (const ShapeMover& m : mine) {
          if (!m.prismatic) growth += stride[m.coordinate] * m.multiplier * m.growth.dot(absStep);
        }
        for (int t = 1; t <= kSteps; ++t) {
          const Eigen::VectorXd before = q0 + (t - 1) * step, after = q0 + t * step;
          const double moved = farthestMove(robot, s, points, relativeTo, before, after, a, b);
          ASSERT_LE(moved, speed + t * growth + 1e-9)
              << robot.name() << " shape " << s << " relative to link " << relativeTo << ", step "
              << t;
        }
      }
    }
  }
}

TEST(ShapeLevers, SpeedsAtAConfigurationBoundHowFarItsShapesMoveNearIt) {
  Rng rng(13);
  expectSpeedsHold(slider(), rng, 200);
  for (const RobotEntry& entry : shippedRobots()) expectSpeedsHold(loadRobot(entry.name), rng, 10);
}

TEST(ShapeLevers, BoundHowFarEveryShapeMoves) {
  Rng rng(11);
  const Robot s = slider();
  expectLeversHold(s, rng, 300);
  // The tip follows `turn` twice over through the mimic, and the lift one to one.
  const Eigen::VectorXd tip = shapeLevers(s, 3, coveringBalls(s.shapes()[3].shape), s.rootLink());
  EXPECT_DOUBLE_EQ(tip[0], 1.0);
  EXPECT_GT(tip[1], 2 * 0.4);
  // Relative to its own link a shape does not move; a link below it is no ancestor.
  EXPECT_TRUE(shapeLevers(s, 3, coveringBalls(s.shapes()[3].shape), 3).isZero());
  EXPECT_THROW(shapeLevers(s, 1, coveringBalls(s.shapes()[1].shape), 3), InvalidArgument);
  EXPECT_EQ(commonAncestor(s, 3, 1), 1);
  EXPECT_EQ(commonAncestor(s, 0, 3), 0);
  for (const RobotEntry& entry : shippedRobots()) expectLeversHold(loadRobot(entry.name), rng, 20);
}

/// Boxes of 4 to 30 cm scattered within the robot's reach.
Scene clutter(Rng& rng, int boxes, double reach) {
  std::uniform_real_distribution<double> at(-reach, reach), size(0.04, 0.3), angle(-3, 3);
  Scene scene;
  for (int i = 0; i < boxes; ++i) {
    const Eigen::Isometry3d pose = Eigen::Translation3d(at(rng), at(rng), at(rng) / 2 + reach / 2) *
                                   Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitZ());
    scene.add(
        {"box" + std::to_string(i), Box{{size(rng), size(rng), size(rng)}}, pose, std::nullopt});
  }
  return scene;
}

/// `boxes` boxes among which `robot` has some free room (boxes on the fixed links make none free),
/// spanning the robot's size: its shapes' farthest reach at the zero configuration. Of the
/// clutters tried, the one with the most free configurations (at least 10 of 50 ends the search).
Scene clutterWithFreeRoom(const Robot& robot, Rng& rng, int boxes = 8) {
  double reach = 0;
  const KinematicsData zero = kinematicsAtZero(robot);
  for (std::size_t s = 0; s < robot.shapes().size(); ++s) {
    reach = std::max(reach, shapePose(robot, zero, s).translation().norm() +
                                boundingRadius(robot.shapes()[s].shape));
  }
  Scene scene;
  std::ptrdiff_t mostFree = -1;
  for (int attempt = 0; attempt < 100 && mostFree < 10; ++attempt) {
    Scene candidate = clutter(rng, boxes, reach);
    // The broad phase alone: no ball covers to build for each clutter tried.
    const FclChecker probe(robot, candidate, {.selfCollision = true, .proveMotionsFree = false});
    const auto answers = probe.inCollisionBatch(uniformConfigurations(robot.limits(), 50, rng));
    const std::ptrdiff_t free = std::count(answers.begin(), answers.end(), 0);
    if (free > mostFree) {
      mostFree = free;
      scene = std::move(candidate);
    }
  }
  EXPECT_GE(mostFree, 3) << robot.name() << ": every clutter tried leaves it hardly a free place";
  return scene;
}

// The property the certificate must keep: the same verdict as checking every state, on motions
// that start free, of every length, among obstacles, with self-collision, on every shipped robot
// (300 per robot; 100 under the sanitizers).
TEST(CertifiedMotion, AnswersAsTheDenseCheckOnEveryShippedRobot) {
  Rng rng(5);
  for (const RobotEntry& entry : shippedRobots()) {
    const Robot robot = loadRobot(entry.name);
    const JointLimits limits = robot.limits();
    const Scene scene = clutterWithFreeRoom(robot, rng);
    const FclChecker dense(robot, scene, {.selfCollision = true, .proveMotionsFree = false});
    const FclChecker certified(robot, scene, {.selfCollision = true});
    ASSERT_TRUE(certified.provesMotionsFree());
    ASSERT_FALSE(dense.provesMotionsFree());
    const std::size_t dim = robot.dof();
    std::size_t colliding = 0, motions = 0, looked = 0, states = 0;
    for (int draws = 0; motions < kMotions; ++draws) {
      ASSERT_LT(draws, 100000) << entry.name << ": no free configuration among the clutter";
      const Eigen::VectorXd from = uniformConfigurations(limits, 1, rng).row(0).transpose();
      if (dense.inCollision(std::span<const double>(from.data(), dim))) continue;
      const Eigen::VectorXd to = motionEnd(from, limits, 0.05, 2.0, rng);
      const std::size_t n = segmentCount(from.data(), to.data(), dim, 0.03);
      const bool denseHit = denseMotionCollides(dense, from, to, n);
      const CollisionChecker::MotionCheck answer =
          certified.motionCollision(from.data(), to.data(), n);
      ASSERT_EQ(answer.collidingState != 0, denseHit)
          << entry.name << ": motion " << motions << " of " << n << " segments";
      if (answer.collidingState != 0) {  // the state named does collide
        std::vector<double> q(dim);
        motionState(from.data(), to.data(), dim, answer.collidingState, n, q.data());
        ASSERT_TRUE(dense.inCollision(q)) << entry.name;
        ++colliding;
      }
      looked += answer.looked;
      states += n;
      ++motions;
    }
    // Both kinds of motion were met, and the certificate skipped states.
    EXPECT_GT(colliding, kMotions / 30) << entry.name;
    EXPECT_LT(colliding, kMotions - kMotions / 30) << entry.name;
    EXPECT_LT(looked, states) << entry.name;
    std::cout << entry.name << ": " << colliding << " of " << kMotions
              << " motions collide; looked at " << looked << " of " << states << " states\n";
  }
}

// A path's edges share their waypoints: a motion that starts where the last one ended reads the
// bounds kept at that end (MotionScratch::endBounds) instead of placing the robot there again. The
// same verdicts as the dense check along a walk of free waypoints, and fewer states placed than the
// same walk with the kept bounds thrown away before each edge (an unrelated motion in between).
TEST(CertifiedMotion, AMotionFromTheLastEndReadsItsBoundsWithTheSameVerdicts) {
  Rng rng(11);
  for (const RobotEntry& entry : shippedRobots()) {
    const Robot robot = loadRobot(entry.name);
    const JointLimits limits = robot.limits();
    const Scene scene = clutterWithFreeRoom(robot, rng);
    const FclChecker dense(robot, scene, {.selfCollision = true, .proveMotionsFree = false});
    const FclChecker chained(robot, scene, {.selfCollision = true});
    const FclChecker fresh(robot, scene, {.selfCollision = true});
    const std::size_t dim = robot.dof();
    const auto freeConfiguration = [&] {
      for (int draws = 0; draws < 100000; ++draws) {
        const Eigen::VectorXd q = uniformConfigurations(limits, 1, rng).row(0).transpose();
        if (!dense.inCollision(std::span<const double>(q.data(), dim))) return q;
      }
      ADD_FAILURE() << entry.name << ": no free configuration among the clutter";
      return Eigen::VectorXd(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dim)));
    };
    const Eigen::VectorXd aside = freeConfiguration();
    Eigen::VectorXd from = freeConfiguration();
    std::size_t chainedLooked = 0, freshLooked = 0, edges = 0;
    for (std::size_t m = 0; m < kMotions / 2; ++m) {
      const Eigen::VectorXd to = motionEnd(from, limits, 0.05, 0.6, rng);
      const std::size_t n = segmentCount(from.data(), to.data(), dim, 0.03);
      const bool denseHit = denseMotionCollides(dense, from, to, n);
      const auto a = chained.motionCollision(from.data(), to.data(), n);
      fresh.motionCollision(from.data(), aside.data(), 1);  // keeps another end
      const auto b = fresh.motionCollision(from.data(), to.data(), n);
      ASSERT_EQ(a.collidingState != 0, denseHit) << entry.name << ": motion " << m;
      ASSERT_EQ(b.collidingState != 0, denseHit) << entry.name << ": motion " << m;
      if (denseHit) {  // the walk goes on from a free configuration: no bounds kept
        from = freeConfiguration();
        continue;
      }
      chainedLooked += a.looked;
      freshLooked += b.looked;
      ++edges;
      from = to;
    }
    EXPECT_GT(edges, 0U) << entry.name;
    // Each free edge after the first skips placing its start once.
    EXPECT_LT(chainedLooked, freshLooked) << entry.name;
  }
}

// A configuration's check skips the pairs that bounds keep apart: the same answers as FCL asked
// about every pair (its broad phase, then its narrow phase), with and without self-collision, on
// uniform configurations and on the states of motions among the clutter, which pass close to
// surfaces, on every shipped robot.
TEST(CertifiedState, AnswersAsEveryPairCheckedOnEveryShippedRobot) {
  std::uint64_t seed = 60;
  for (const RobotEntry& entry : shippedRobots()) {
    const Robot robot = loadRobot(entry.name);
    const JointLimits limits = robot.limits();
    // A generator per robot: its clutter does not hang on the states drawn for the robots before.
    Rng rng(++seed);
    // As many boxes as keep the robot's shape-obstacle pairs within what the bounds take on
    // (256; beyond, FCL's broad phase answers alone and there is nothing to compare), up to 16.
    const int boxes = std::clamp(256 / static_cast<int>(robot.shapes().size()), 4, 16);
    const Scene scene = clutterWithFreeRoom(robot, rng, boxes);
    const std::size_t dim = robot.dof();
    // Uniform configurations (3000; 1000 under the sanitizers), then every state of a motion
    // between two of them (30; 10).
    const Configurations ends = uniformConfigurations(limits, 10 * kMotions, rng);
    std::vector<double> states(ends.data(), ends.data() + ends.size());
    std::vector<double> motion;
    for (Eigen::Index m = 0; m + 1 < static_cast<Eigen::Index>(kMotions / 5); m += 2) {
      const Eigen::VectorXd from = ends.row(m).transpose(), to = ends.row(m + 1).transpose();
      motionStates(from.data(), to.data(), dim, segmentCount(from.data(), to.data(), dim, 0.03),
                   motion);
      states.insert(states.end(), motion.begin(), motion.end());
    }
    const std::size_t n = states.size() / dim;
    for (const bool self : {false, true}) {
      const FclChecker everyPair(robot, scene, {.selfCollision = self, .proveMotionsFree = false});
      const FclChecker bounded(robot, scene, {.selfCollision = self});
      ASSERT_TRUE(bounded.boundsStateChecks()) << entry.name;
      ASSERT_FALSE(everyPair.boundsStateChecks()) << entry.name;
      std::vector<std::uint8_t> expected(n), answers(n);
      everyPair.inCollisionEach(states.data(), n, expected.data());
      bounded.inCollisionEach(states.data(), n, answers.data());
      const auto colliding = std::count(expected.begin(), expected.end(), 1);
      // Both kinds met. The clutters differ between compilers (the search keeps the clutter with
      // the most free room; rounding decides ties): the fewest colliding were the mobile arm's
      // obstacles alone in the Release build (71 of 7986), the mesh Panda's in the sanitizer
      // build (6 of about 2700).
      EXPECT_GT(colliding, 0) << entry.name;
      EXPECT_LT(colliding, static_cast<std::ptrdiff_t>(n - n / 200)) << entry.name;
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(answers[i], expected[i])
            << entry.name << (self ? " with" : " without") << " self-collision, state " << i;
      }
      // One at a time (check, firstInCollision) as in a run.
      for (std::size_t i = 0; i < n; i += 7) {
        ASSERT_EQ(bounded.inCollision(std::span<const double>(states.data() + i * dim, dim)),
                  expected[i] != 0)
            << entry.name << ", state " << i;
      }
      EXPECT_EQ(bounded.firstInCollision(states.data(), n),
                everyPair.firstInCollision(states.data(), n))
          << entry.name;
    }
  }
}

/// A robot of one shape that moves freely: three prismatic joints, then two turns.
Robot freeShape(const Shape& shape) {
  std::vector<Joint> joints{
      joint("x", JointType::Prismatic, 0, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), -1, 1),
      joint("y", JointType::Prismatic, 1, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), -1, 1),
      joint("z", JointType::Prismatic, 2, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), -1, 1),
      joint("yaw", JointType::Revolute, 3, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), -3,
            3),
      joint("pitch", JointType::Revolute, 4, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), -3,
            3)};
  return Robot("free " + describe(shape), {{"base"}, {"x"}, {"y"}, {"z"}, {"yaw"}, {"pitch"}},
               std::move(joints), {{5, Eigen::Isometry3d::Identity(), shape}});
}

// What lets a configuration's check skip FCL where a robot shape is in an obstacle: a ball inside
// the shape that reaches into the obstacle means FCL finds the pair touching, for every kind of
// robot shape against every kind of obstacle the proof reads, at thousands of placements about
// the obstacle; and the proof finds most of FCL's touches.
TEST(CertifiedState, ABallInsideAShapeThatReachesIntoAnObstacleIsATouchFclFinds) {
  const std::vector<Shape> robotShapes{Box{{0.3, 0.1, 0.05}}, Sphere{0.08}, Cylinder{0.05, 0.3},
                                       Capsule{0.04, 0.25}, tubeMesh()};
  const std::vector<Shape> obstacles{Box{{0.4, 0.3, 0.05}}, Sphere{0.15}, Cylinder{0.1, 0.5},
                                     Capsule{0.05, 0.4}};
  const Eigen::Isometry3d pose = Eigen::Translation3d(0.05, -0.02, 0.03) *
                                 Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  Rng rng(23);
  const std::size_t samples = kMotions * 4;
  for (const Shape& shape : robotShapes) {
    const Robot robot = freeShape(shape);
    const BallCover cover = coveringBallTree(shape);
    BallColumns inside;
    for (const Shape& obstacleShape : obstacles) {
      Scene scene;
      scene.add({"obstacle", obstacleShape, pose, std::nullopt});
      const FclChecker fcl(robot, scene, {.proveMotionsFree = false});
      const EnclosingVolume obstacle(obstacleShape, pose);
      KinematicsData kinematics = makeKinematicsData(robot);
      // Placements within 25 cm of the obstacle's centre, so that many touch it.
      Eigen::VectorXd lower = robot.limits().lower(), upper = robot.limits().upper();
      lower.head<3>().setConstant(-0.25);
      upper.head<3>().setConstant(0.25);
      const JointLimits near(lower, upper);
      const Configurations qs = uniformConfigurations(near, samples, rng);
      std::size_t touching = 0, proven = 0;
      for (Eigen::Index i = 0; i < qs.rows(); ++i) {
        const Eigen::VectorXd q = qs.row(i).transpose();
        forwardKinematics(robot, q.data(), kinematics);
        inside.place(shapePose(robot, kinematics, 0), cover.inside);
        const bool proof = obstacle.reachedBy(inside, 1e-4);
        const bool touches = fcl.inCollision(std::span<const double>(q.data(), 5));
        if (proof) {
          ASSERT_TRUE(touches) << describe(shape) << " in " << describe(obstacleShape) << " at "
                               << q.transpose();
        }
        touching += touches ? 1 : 0;
        proven += proof ? 1 : 0;
      }
      EXPECT_GT(touching, samples / 10) << describe(shape) << " in " << describe(obstacleShape);
      EXPECT_GT(proven, touching / 3) << describe(shape) << " in " << describe(obstacleShape);
    }
  }
}

TEST(CertifiedMotion, AMotionWhoseEndCollidesIsFoundAtItsEnd) {
  const Robot robot = slider();
  Scene scene;
  scene.add({"wall", Box{{0.1, 2, 2}}, Eigen::Isometry3d(Eigen::Translation3d(0.55, 0, 0)),
             std::nullopt});
  const FclChecker checker(robot, scene);
  const std::vector<double> from{0, 1.5}, to{0, 0};  // the arm swings into the wall
  const auto answer = checker.motionCollision(from.data(), to.data(), 50);
  EXPECT_EQ(answer.collidingState, 50u);
  EXPECT_EQ(answer.looked, 1u);
  // A prismatic coordinate beyond its limits: no proof, every state looked at, same answer.
  const std::vector<double> below{-0.5, 1.5}, stillBelow{-0.5, 1.4};
  EXPECT_EQ(checker.motionCollision(below.data(), stillBelow.data(), 10).looked, 10u);
  const std::vector<double> bad{0, std::nan("")};
  EXPECT_THROW(checker.motionCollision(from.data(), bad.data(), 5), InvalidArgument);
}

// FCL's GJK can answer a grazing pair differently by the order it is handed the two shapes, so
// the certificate asks an obstacle pair in the dense check's order (the broad phase's: the
// obstacle first). The mobile arm's forearm (a capsule) grazing a wall of a generated cage
// (`fastron problems --robot mobile-arm --family cage -n 10 --seed 7`, problem 4, the tenth query
// of `bench motion-bench --queries-per-scene 10`): state 2 of this edge of FCL's own path overlaps
// the wall (FCL's distance: -1), which only the wall-first order saw.
TEST(CertifiedMotion, AsksAGrazingPairInTheDenseChecksOrder) {
  Robot robot = loadRobot("mobile-arm");
  robot.setActuatedJoints({"torso_lift_joint", "shoulder_pan_joint", "shoulder_lift_joint",
                           "upperarm_roll_joint", "elbow_flex_joint", "forearm_roll_joint",
                           "wrist_flex_joint", "wrist_roll_joint"});
  Scene scene;
  Eigen::Isometry3d wall = Eigen::Isometry3d::Identity();
  wall.translation() = Eigen::Vector3d(0.8432918441750911, -0.3712263339030187, 0.5988586781073975);
  wall.linear() =
      Eigen::Quaterniond(0.9993560810733637, 0, 0, -0.035880680340378196).toRotationMatrix();
  scene.add({"side_left", Box{{0.7, 0.04, 0.7}}, wall, std::nullopt});
  const FclChecker certified(robot, scene);
  const FclChecker dense(robot, scene, CheckerOptions{.proveMotionsFree = false});
  ASSERT_TRUE(certified.provesMotionsFree());
  const std::vector<double> from{0.22327929363252338, -0.57446280850116016, 0.90995594680169711,
                                 0.66078595299188492, -0.76093724502666249, -1.1894072485497906,
                                 0.38063690291927749, -1.4029501078419797};
  const std::vector<double> to{0.21881486906836026, -0.63404265008178229, 0.87898400017220579,
                               0.55527404433647898, -0.69529173970762292, -0.93866431635473713,
                               0.25703645635380667, -1.1826664310063557};
  constexpr std::size_t kSegments = 13;
  std::vector<double> state(robot.dof());
  motionState(from.data(), to.data(), robot.dof(), 2, kSegments, state.data());
  EXPECT_TRUE(dense.inCollision(state)) << "FCL no longer sees the graze: a new case is needed";
  const bool denseFinds =
      dense.motionCollision(from.data(), to.data(), kSegments).collidingState != 0;
  EXPECT_EQ(certified.motionCollision(from.data(), to.data(), kSegments).collidingState != 0,
            denseFinds);
}

}  // namespace
}  // namespace fastron
