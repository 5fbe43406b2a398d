#include "fastron/geometry/gjk_checker.h"

#include <ccd/ccd.h>

#include "fastron/core/error.h"
#include "fastron/geometry/kinematics.h"
#include "overloaded.h"

namespace fastron {
namespace {

double sign(double v) {
  return v < 0 ? -1.0 : 1.0;
}

void supportCallback(const void* body, const ccd_vec3_t* direction, ccd_vec3_t* out) {
  const Eigen::Vector3d d(direction->v[0], direction->v[1], direction->v[2]);
  const Eigen::Vector3d p = static_cast<const ConvexBody*>(body)->support(d);
  ccdVec3Set(out, p.x(), p.y(), p.z());
}

void centreCallback(const void* body, ccd_vec3_t* out) {
  const Eigen::Vector3d c = static_cast<const ConvexBody*>(body)->pose.translation();
  ccdVec3Set(out, c.x(), c.y(), c.z());
}

void firstDirection(const void* a, const void* b, ccd_vec3_t* out) {
  Eigen::Vector3d d = static_cast<const ConvexBody*>(b)->pose.translation() -
                      static_cast<const ConvexBody*>(a)->pose.translation();
  if (d.squaredNorm() < 1e-24) d = Eigen::Vector3d::UnitX();
  ccdVec3Set(out, d.x(), d.y(), d.z());
}

}  // namespace

ConvexBody ConvexBody::from(const Shape& shape) {
  ConvexBody body;
  std::visit(Overloaded{
                 [&](const Box& b) {
                   body.kind = Kind::Box;
                   body.halfSize = b.size / 2;
                 },
                 [&](const Sphere& s) {
                   body.kind = Kind::Sphere;
                   body.radius = s.radius;
                 },
                 [&](const Cylinder& c) {
                   body.kind = Kind::Cylinder;
                   body.radius = c.radius;
                   body.halfLength = c.length / 2;
                 },
                 [&](const Capsule& c) {
                   body.kind = Kind::Capsule;
                   body.radius = c.radius;
                   body.halfLength = c.length / 2;
                 },
                 [](const PointCloud&) {
                   throw Unsupported("the GJK checker does not check point clouds (use fcl)");
                 },
                 [&](const Mesh& m) {
                   body.kind = Kind::Hull;
                   // Shares the mesh's vertices (aliasing): moving a scene copies nothing.
                   body.hull = std::shared_ptr<const std::vector<Eigen::Vector3d>>(
                       m.mesh, &m.mesh->vertices);
                 },
             },
             shape);
  return body;
}

Eigen::Vector3d ConvexBody::support(const Eigen::Vector3d& direction) const {
  const Eigen::Vector3d d = pose.linear().transpose() * direction;  // into the body frame
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  switch (kind) {
    case Kind::Box:
      p = Eigen::Vector3d(sign(d.x()) * halfSize.x(), sign(d.y()) * halfSize.y(),
                          sign(d.z()) * halfSize.z());
      break;
    case Kind::Sphere:
      p = d.norm() > 0 ? Eigen::Vector3d(radius * d.normalized()) : Eigen::Vector3d(radius, 0, 0);
      break;
    case Kind::Cylinder: {
      // Not std::hypot: its care for overflow made it 8% of `fastron demo`'s samples (perf), and
      // libccd's directions are differences of points a few metres apart.
      const double planar = d.head<2>().norm();
      if (planar > 0) p.head<2>() = radius * d.head<2>() / planar;
      p.z() = sign(d.z()) * halfLength;
      break;
    }
    case Kind::Capsule:
      p = Eigen::Vector3d(0, 0, sign(d.z()) * halfLength);
      if (d.norm() > 0) p += radius * d.normalized();
      break;
    case Kind::Hull: {
      double best = -std::numeric_limits<double>::infinity();
      for (const auto& v : *hull) {
        const double score = v.dot(d);
        if (score > best) {
          best = score;
          p = v;
        }
      }
      break;
    }
  }
  return pose * p;
}

bool gjkIntersect(const ConvexBody& a, const ConvexBody& b) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = supportCallback;
  ccd.support2 = supportCallback;
  ccd.center1 = centreCallback;
  ccd.center2 = centreCallback;
  ccd.first_dir = firstDirection;
  ccd.max_iterations = 100;
  return ccdGJKIntersect(&a, &b, &ccd) != 0;
}

struct GjkChecker::Scratch {
  KinematicsData kinematics;
  std::vector<ConvexBody> robot;
};

struct GjkChecker::World {
  std::vector<ConvexBody> obstacles;
  std::vector<std::string> names;  // the obstacles'
  Eigen::Isometry3d robotBase = Eigen::Isometry3d::Identity();
  std::vector<std::pair<std::size_t, std::size_t>> selfPairs;  // pairs a configuration can change
  std::vector<std::uint8_t> allowed;                           // see allowedObstacleContacts
  // The robot's shapes placed where every configuration puts the ones that do not move (the
  // moving ones are placed per check, in Scratch). One of those touches an obstacle or another
  // such shape, in this scene: every configuration collides (found once here, as in FclChecker).
  std::vector<ConvexBody> fixedBodies;
  std::optional<Touch> fixedTouch;

  /// Robot shape `shape` as placed for the configuration in `scratch`, or here if it does not move.
  const ConvexBody& robotBody(const Scratch& scratch, std::size_t shape, bool moves) const;
};

GjkChecker::GjkChecker(Robot robot, const Scene& scene, CheckerOptions options)
    : robot_(std::move(robot)), options_(options), scratch_([this] {
        auto s = std::make_unique<Scratch>();
        s->kinematics = makeKinematicsData(robot_);
        s->robot = robotBodies_;
        return s;
      }) {
  if (robot_.dof() == 0)
    throw InvalidArgument("GjkChecker: robot '" + robot_.name() + "' has no actuated joints");
  for (std::size_t s = 0; s < robot_.shapes().size(); ++s) {
    ConvexBody body = ConvexBody::from(paddedShape(robot_, s, options_));
    body.pose = robot_.shapes()[s].origin;
    robotBodies_.push_back(std::move(body));
  }
  shapeMoves_ = shapesMovedByConfiguration(robot_);
  setScene(scene);
}

GjkChecker::~GjkChecker() = default;

void GjkChecker::setScene(const Scene& scene) {
  auto next = std::make_shared<World>();
  next->robotBase = scene.robotBase;
  for (const Obstacle& o : scene.obstacles()) {
    if (std::holds_alternative<PointCloud>(o.shape))
      throw Unsupported("obstacle '" + o.name +
                        "' is a point cloud, which the GJK checker does not check (use fcl)");
    ConvexBody body = ConvexBody::from(o.shape);
    body.pose = o.pose;
    next->obstacles.push_back(std::move(body));
    next->names.push_back(o.name);
  }
  next->allowed = allowedObstacleContacts(robot_, scene);
  const KinematicsData kinematics = kinematicsAtZero(robot_, next->robotBase);
  std::vector<ConvexBody>& fixed = next->fixedBodies;
  fixed = robotBodies_;
  for (std::size_t s = 0; s < fixed.size(); ++s) {
    if (shapeMoves_[s] != 0) continue;
    fixed[s].pose = shapePose(robot_, kinematics, s);
    const auto obstacle = touchedObstacle(*next, fixed[s], s);
    if (obstacle && !next->fixedTouch) next->fixedTouch = Touch{s, *obstacle, false};
  }
  if (options_.selfCollision) {
    for (const auto& [a, b] : robot_.selfCollisionPairs(scene.allowedCollisions)) {
      if (shapeMoves_[a] != 0 || shapeMoves_[b] != 0) {
        next->selfPairs.emplace_back(a, b);
      } else if (!next->fixedTouch && gjkIntersect(fixed[a], fixed[b])) {
        next->fixedTouch = Touch{a, b, true};
      }
    }
  }
  world_.set(std::move(next));
}

const ConvexBody& GjkChecker::World::robotBody(const Scratch& scratch, std::size_t shape,
                                               bool moves) const {
  return moves ? scratch.robot[shape] : fixedBodies[shape];
}

std::optional<std::size_t> GjkChecker::touchedObstacle(const World& world, const ConvexBody& body,
                                                       std::size_t shape) const {
  const std::size_t count = world.obstacles.size();
  for (std::size_t o = 0; o < count; ++o) {
    if (!world.allowed.empty() && world.allowed[shape * count + o] != 0) continue;
    if (gjkIntersect(body, world.obstacles[o])) return o;
  }
  return std::nullopt;
}

bool GjkChecker::check(const double* q) const {
  return checkFirst(q, 1) == 0;
}

// One read of the world and one scratch lease for the whole run, as FclChecker::checkFirst.
std::size_t GjkChecker::checkFirst(const double* q, std::size_t n) const {
  const std::shared_ptr<const World> world = world_.get();
  auto scratch = scratch_.lease();
  for (std::size_t i = 0; i < n; ++i) {
    if (firstTouch(*world, *scratch, q + i * robot_.dof())) return i;
  }
  return n;
}

void GjkChecker::checkEach(const double* q, std::size_t n, std::uint8_t* out) const {
  const std::shared_ptr<const World> world = world_.get();
  auto scratch = scratch_.lease();
  for (std::size_t i = 0; i < n; ++i)
    out[i] = firstTouch(*world, *scratch, q + i * robot_.dof()).has_value();
}

std::optional<Contact> GjkChecker::contactAt(const double* q) const {
  const std::shared_ptr<const World> world = world_.get();
  auto scratch = scratch_.lease();
  const std::optional<Touch> touch = firstTouch(*world, *scratch, q);
  if (!touch) return std::nullopt;
  return Contact{robot_.shapeLinkName(touch->shape),
                 touch->self ? robot_.shapeLinkName(touch->other) : world->names[touch->other],
                 touch->self};
}

std::optional<GjkChecker::Touch> GjkChecker::firstTouch(const World& world, Scratch& scratch,
                                                        const double* q) const {
  if (world.fixedTouch) return world.fixedTouch;
  forwardKinematics(robot_, q, scratch.kinematics, world.robotBase);
  const auto& shapes = robot_.shapes();
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    if (shapeMoves_[s] == 0) continue;  // placed and checked by setScene
    scratch.robot[s].pose =
        scratch.kinematics.linkPoses[static_cast<std::size_t>(shapes[s].link)] * shapes[s].origin;
    if (const auto obstacle = touchedObstacle(world, scratch.robot[s], s))
      return Touch{s, *obstacle, false};
  }
  for (const auto& [a, b] : world.selfPairs) {
    if (gjkIntersect(world.robotBody(scratch, a, shapeMoves_[a] != 0),
                     world.robotBody(scratch, b, shapeMoves_[b] != 0)))
      return Touch{a, b, true};
  }
  return std::nullopt;
}

}  // namespace fastron
