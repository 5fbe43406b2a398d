#include "fastron/geometry/fcl_checker.h"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <string>

#include "fastron/core/error.h"
#include "fastron/core/parallel_chunks.h"
#include "fastron/geometry/clearance_bounds.h"
#include "fastron/geometry/cloud_grid.h"
#include "fastron/geometry/kinematics.h"
#include "overloaded.h"

namespace fastron {
namespace {

using FclGeometry = std::shared_ptr<fcl::CollisionGeometryd>;

/// A configuration's check bounds each robot shape-obstacle pair in turn where there are at most
/// this many, and leaves more to FCL's broad phase (an AABB tree, whose walk grows with the log of
/// the obstacles). Against boxes near the robot (BM_Check, BM_CheckFree; docs/performance.md) the
/// bounds were 0.9-1.7 times as fast as the broad phase up to 10 obstacles on every shipped robot
/// and 1.0-1.8 times at 30 where the limit lets them; with the limit lifted, among 100 boxes, 0.6
/// times on Baxter and the Panda, where most configurations collide and the bounds go pair by pair
/// to the colliding one (Baxter's 10 moving shapes among 30 boxes, 300 pairs: 0.9-1.1 times).
constexpr std::ptrdiff_t kMaxProvenStatePairs = 256;

/// True when neither shape is a mesh: FCL's distance between them is a GJK run, cheap enough for
/// checkMotion's bounds (between meshes it walks two hierarchies: on the mesh Panda, verification
/// asking it took 3.6 times longer than checking every state, 3.9 times with FCL's rel_err 1).
bool primitives(const Shape& a, const Shape& b) {
  return !std::holds_alternative<Mesh>(a) && !std::holds_alternative<Mesh>(b);
}

/// A mesh's bounding-volume hierarchy for collision checks or for distances. Collision checks use
/// OBBs: for a mesh against a box FCL computes the box's bounding volume anew on every test, which
/// for an OBBRSS hierarchy is an eigen-decomposition of the box's corners and for an OBB is the
/// box's own frame (the mesh Panda's checks in a cage scene: 20.5 µs with OBBRSS, 3.3-4.3 µs with
/// OBB). FCL computes no distance between OBBs, so distances use an OBBRSS hierarchy of the same
/// triangles, built beside it (no start-up cost measurable in `fastron check`).
enum class Hierarchy { Collision, Distance };

template <class BoundingVolume>
FclGeometry meshHierarchy(const TriangleMesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<BoundingVolume>>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    triangles.emplace_back(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                           static_cast<std::size_t>(t[2]));
  }
  model->beginModel();
  model->addSubModel(mesh.vertices, triangles);
  model->endModel();
  return model;
}

FclGeometry toFcl(const Shape& shape, Hierarchy hierarchy) {
  return std::visit(
      Overloaded{
          [](const Box& b) -> FclGeometry { return std::make_shared<fcl::Boxd>(b.size); },
          [](const Sphere& s) -> FclGeometry { return std::make_shared<fcl::Sphered>(s.radius); },
          [](const Cylinder& c) -> FclGeometry {
            return std::make_shared<fcl::Cylinderd>(c.radius, c.length);
          },
          // FCL's capsule length is the cylinder part only, as ours.
          [](const Capsule& c) -> FclGeometry {
            return std::make_shared<fcl::Capsuled>(c.radius, c.length);
          },
          [&](const Mesh& m) -> FclGeometry {
            return hierarchy == Hierarchy::Collision ? meshHierarchy<fcl::OBBd>(*m.mesh)
                                                     : meshHierarchy<fcl::OBBRSSd>(*m.mesh);
          },
          // Clouds are checked beside FCL's broad phase (FclChecker::Cloud), not by it.
          [](const PointCloud&) -> FclGeometry { return nullptr; },
      },
      shape);
}

/// A shape's geometry for collision checks and for distances: the same object for a primitive.
struct FclGeometries {
  FclGeometry collision, distance;
};

FclGeometries geometriesOf(const Shape& shape) {
  FclGeometries g{toFcl(shape, Hierarchy::Collision), nullptr};
  g.distance =
      std::holds_alternative<Mesh>(shape) ? toFcl(shape, Hierarchy::Distance) : g.collision;
  return g;
}

fcl::Transform3d toFcl(const Eigen::Isometry3d& pose) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = pose.linear();
  t.translation() = pose.translation();
  return t;
}

/// FCL's object of a robot shape moved to `pose`, with its box for the broad phase.
void placeObject(fcl::CollisionObjectd& object, const Eigen::Isometry3d& pose) {
  object.setTransform(toFcl(pose));
  object.computeAABB();
}

// Broad-phase callback: stop at the first collision and remember the obstacle it was; skip the
// obstacles this robot shape may touch.
struct CollideData {
  const fcl::CollisionObjectd* hit = nullptr;
  const std::uint8_t* allowed = nullptr;  // one flag per obstacle, or none
};

// Obstacles carry their index + 1 as user data; robot objects carry none.
std::size_t obstacleIndex(const fcl::CollisionObjectd* object) {
  return reinterpret_cast<std::size_t>(object->getUserData()) - 1;
}

// Two shapes, placed and with their AABBs computed; FCL is handed `a` first.
bool shapesTouch(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b) {
  if (!a.getAABB().overlap(b.getAABB())) return false;
  const fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(&a, &b, request, result);
  return result.isCollision();
}

// An obstacle and a robot shape: every check of such a pair (the broad phase's, the clearance
// certificate's) asks FCL in this one order. Its GJK can answer a grazing pair differently in the
// other: a capsule and a box that its distance found overlapping touched only with the box first,
// and a planner's motion was proven free that the dense check found colliding
// (CertifiedMotion.AsksAGrazingPairInTheDenseChecksOrder).
bool obstacleTouches(const fcl::CollisionObjectd& obstacle, const fcl::CollisionObjectd& shape) {
  return shapesTouch(obstacle, shape);
}

bool collideCallback(fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* raw) {
  auto* data = static_cast<CollideData*>(raw);
  if (data->hit != nullptr) return true;
  const bool aIsObstacle = a->getUserData() != nullptr;
  const fcl::CollisionObjectd* obstacle = aIsObstacle ? a : b;
  if (data->allowed != nullptr && data->allowed[obstacleIndex(obstacle)] != 0) return false;
  if (obstacleTouches(*obstacle, aIsObstacle ? *b : *a)) data->hit = obstacle;
  return data->hit != nullptr;
}

}  // namespace

struct FclChecker::Geometry {
  std::vector<FclGeometries> shapes;  // one per robot shape, padded
  // For clouds: each padded shape's exact distance from a point (a primitive's), or a lower bound
  // on it (the box around a mesh's vertices, whose triangles FCL then asks), in the shape's frame;
  // and how far from the root's origin any point of a shape can be.
  std::vector<EnclosingVolume> volumes;
  std::vector<std::uint8_t> meshes;
  double reach = 0;
  std::vector<std::uint8_t> moves;  // shapesMovedByConfiguration
  std::vector<std::size_t> moving;  // the shapes that move, in shape order
  // For clearance bounds, with options.proveMotionsFree only: balls covering each padded shape,
  // and each shape's levers relative to the robot's root.
  std::shared_ptr<const std::vector<BallCover>> balls;
  std::vector<Eigen::VectorXd> levers;
  // Each shape's movers relative to the root, their growth from its enclosing ball (whose
  // points' distance from an axis PlacedBalls::speed measures).
  std::shared_ptr<const std::vector<std::vector<ShapeMover>>> movers;
  // With self-collision: tables of the distance of self pairs of meshes that one or two
  // coordinates turn against each other (options.selfPairTables, or built for selfPairSlack).
  std::shared_ptr<const std::vector<SelfPairTable>> selfTables;
  // Coordinates of prismatic joints with their limits: the levers hold within them.
  std::vector<std::tuple<std::size_t, double, double>> prismatic;
};

/// A point-cloud obstacle: its balls' centres (world frame, cropped to the robot's reach) in a
/// grid.
struct FclChecker::Cloud {
  std::size_t obstacle = 0;  // index in the scene
  CloudGrid grid;
  double radius = 0;
  std::shared_ptr<fcl::Sphered> ball;  // of the radius, for FCL's ball-against-mesh tests
  /// The centres as a hierarchy of tiny triangles, for distances from a mesh: one traversal of
  /// two hierarchies instead of a ball-against-mesh distance per point (on the mesh Panda near a
  /// sensed table, a distance took tens of milliseconds so). Built at the first such distance.
  struct Hierarchy {
    std::once_flag built;
    FclGeometry points;
  };
  std::shared_ptr<Hierarchy> hierarchy = std::make_shared<Hierarchy>();
  const fcl::CollisionGeometryd& pointHierarchy() const {
    std::call_once(hierarchy->built, [&] {
      // A triangle 1e-7 m across about each centre: distances within 1e-7 m of the point's.
      constexpr double kSide = 1e-7;
      auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
      model->beginModel(static_cast<int>(grid.size()), static_cast<int>(3 * grid.size()));
      for (const Eigen::Vector3d& p : grid.points()) {
        model->addTriangle(p, p + Eigen::Vector3d(kSide, 0, 0), p + Eigen::Vector3d(0, kSide, 0));
      }
      model->endModel();
      hierarchy->points = std::move(model);
    });
    return *hierarchy->points;
  }
};

struct FclChecker::Scratch {
  KinematicsData kinematics;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> robotObjects;
  std::optional<MotionScratch> motion;  // with options.proveMotionsFree: the balls, and more
  // The clearance certificate's questions to FCL on this scratch (exactPairCheck), about `world`
  // (exactPairs sets it): made once per scratch, not per check.
  ExactPairCheck pairs;
  const Obstacles* world = nullptr;
  // The certificate's placement: forward kinematics for every shape, FCL's objects only for the
  // shapes it asks FCL about, each once per configuration (placedAt[s] == placing).
  std::size_t placing = 0;
  std::vector<std::size_t> placedAt;
  // The world whose bounds `motion` keeps at its last motion's end.
  std::uint64_t motionGeneration = 0;
};

struct FclChecker::Obstacles {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
  std::vector<std::string> names;
  fcl::DynamicAABBTreeCollisionManagerd manager;
  Eigen::Isometry3d robotBase = Eigen::Isometry3d::Identity();
  std::vector<std::pair<std::size_t, std::size_t>> selfPairs;  // robot shapes that must not touch
  std::vector<std::pair<std::size_t, std::size_t>> movingSelfPairs;  // of those, the pairs a
                                                                     // configuration can change
  std::vector<std::uint8_t> allowed;                                 // see allowedObstacleContacts
  // The robot shapes no configuration moves (the base, and links joined to it by fixed or held
  // joints), placed once per scene: null for a shape that moves. Their contacts with obstacles and
  // with each other are the same for every configuration, so they are looked for here once: a
  // contact found makes every configuration collide. (Baxter's base, head and torso are 3 of its
  // 13 shapes.)
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> fixedObjects;
  std::optional<Contact> fixedContact;

  /// Robot shape `shape` as placed for the configuration in `scratch`, or here if it does not move.
  const fcl::CollisionObjectd& robotObject(const Scratch& scratch, std::size_t shape) const {
    return fixedObjects[shape] ? *fixedObjects[shape] : *scratch.robotObjects[shape];
  }
  // Mesh obstacles' FCL geometry by mesh, kept from one scene to the next (the mesh is held so
  // that its address cannot name another mesh later).
  std::map<const TriangleMesh*, std::pair<std::shared_ptr<const TriangleMesh>, FclGeometries>>
      meshes;
  std::vector<FclGeometry> distanceShapes;  // of each obstacle, for distance()
  ClearanceModel clearance;                 // for checkMotion
  // A configuration's check bounds every pair first and asks FCL only about the pairs no bound
  // keeps apart (collides), instead of FCL's broad phase; not where a fixed link already touches
  // (every configuration collides, and collide names the contact).
  bool statesProven = false;
  // Point-cloud obstacles; their entries in objects and distanceShapes are null.
  std::vector<Cloud> clouds;
  // Distinct for every world a checker makes (never 0), so that a scratch's carried bounds are
  // never read against a later world that happens to reuse this one's address.
  std::uint64_t generation = nextGeneration();

  static std::uint64_t nextGeneration() {
    static std::atomic<std::uint64_t> last{0};
    return last.fetch_add(1, std::memory_order_relaxed) + 1;
  }
};

FclChecker::FclChecker(Robot robot, const Scene& scene, CheckerOptions options)
    : robot_(std::move(robot)), options_(options), scratch_([this] {
        auto s = std::make_unique<Scratch>();
        s->kinematics = makeKinematicsData(robot_);
        const std::lock_guard lock(objectsOfRobotGeometry_);
        for (const auto& g : geometry_->shapes)
          s->robotObjects.push_back(std::make_unique<fcl::CollisionObjectd>(g.collision));
        if (options_.proveMotionsFree) s->motion.emplace(geometry_->balls);
        s->pairs = exactPairCheck(*s);
        s->placedAt.assign(geometry_->shapes.size(), 0);
        return s;
      }) {
  if (robot_.dof() == 0)
    throw InvalidArgument("FclChecker: robot '" + robot_.name() + "' has no actuated joints");
  if (!(std::isfinite(options_.selfPairSlack) && options_.selfPairSlack >= 0)) {
    throw InvalidArgument("FclChecker: selfPairSlack must be finite and >= 0, not " +
                          std::to_string(options_.selfPairSlack));
  }
  auto geometry = std::make_shared<Geometry>();
  geometry->moves = shapesMovedByConfiguration(robot_);
  auto balls = std::make_shared<std::vector<BallCover>>();
  auto movers = std::make_shared<std::vector<std::vector<ShapeMover>>>();
  for (std::size_t s = 0; s < robot_.shapes().size(); ++s) {
    const Shape padded = paddedShape(robot_, s, options_);
    geometry->shapes.push_back(geometriesOf(padded));
    geometry->volumes.emplace_back(padded, Eigen::Isometry3d::Identity());
    geometry->meshes.push_back(std::holds_alternative<Mesh>(padded) ? 1 : 0);
    if (geometry->moves[s] != 0) geometry->moving.push_back(s);
    if (!options_.proveMotionsFree) continue;
    balls->push_back(coveringBallTree(padded));
    geometry->levers.push_back(shapeLevers(robot_, s, balls->back().balls, robot_.rootLink()));
    movers->push_back(shapeMovers(robot_, s, {balls->back().whole}, robot_.rootLink()));
  }
  geometry->balls = std::move(balls);
  geometry->movers = std::move(movers);
  if (options_.selfCollision && options_.proveMotionsFree) {
    if (options_.selfPairTables) {
      for (const SelfPairTable& table : *options_.selfPairTables) {
        checkSelfPairTable(table, robot_.shapes().size(), robot_.dof(),
                           "FclChecker of robot '" + robot_.name() + "'");
      }
      geometry->selfTables = options_.selfPairTables;
    } else if (options_.selfPairSlack > 0) {
      geometry->selfTables = tabulateSelfPairs(*geometry);
    }
  }
  geometry->reach = reachBound(robot_, options_.padding);
  for (std::size_t k = 0; k < robot_.dof(); ++k) {
    const Joint& joint = robot_.joints()[static_cast<std::size_t>(robot_.actuatedJoints()[k])];
    if (joint.type == JointType::Prismatic)
      geometry->prismatic.emplace_back(k, joint.lower, joint.upper);
  }
  geometry_ = std::move(geometry);
  setScene(scene);
}

FclChecker::~FclChecker() = default;

void FclChecker::setScene(const Scene& scene) {
  auto next = std::make_shared<Obstacles>();
  next->robotBase = scene.robotBase;
  const std::shared_ptr<const Obstacles> previous = obstacles_.get();  // null in the constructor
  const auto geometryOf = [&](const Shape& shape) -> FclGeometries {
    const auto* mesh = std::get_if<Mesh>(&shape);
    if (mesh == nullptr) return geometriesOf(shape);  // primitives cost nothing to make
    if (const auto kept = next->meshes.find(mesh->mesh.get()); kept != next->meshes.end()) {
      return kept->second.second;
    }
    FclGeometries geometry;
    if (previous) {
      if (const auto kept = previous->meshes.find(mesh->mesh.get());
          kept != previous->meshes.end()) {
        geometry = kept->second.second;
      }
    }
    if (!geometry.collision) {
      geometry = geometriesOf(shape);
      ++meshBuilds_;
    }
    next->meshes.emplace(mesh->mesh.get(), std::make_pair(mesh->mesh, geometry));
    return geometry;
  };
  std::vector<fcl::CollisionObjectd*> raw;
  for (std::size_t i = 0; i < scene.obstacles().size(); ++i) {
    const Obstacle& o = scene.obstacles()[i];
    if (const auto* cloud = std::get_if<PointCloud>(&o.shape)) {
      next->clouds.push_back(placeCloud(*cloud, o.pose, scene.robotBase));
      next->clouds.back().obstacle = i;
      next->objects.push_back(nullptr);
      next->names.push_back(o.name);
      next->distanceShapes.push_back(nullptr);
      continue;
    }
    const FclGeometries geometry = geometryOf(o.shape);
    auto object = std::make_unique<fcl::CollisionObjectd>(geometry.collision, toFcl(o.pose));
    object->computeAABB();
    object->setUserData(reinterpret_cast<void*>(i + 1));
    raw.push_back(object.get());
    next->objects.push_back(std::move(object));
    next->names.push_back(o.name);
    next->distanceShapes.push_back(geometry.distance);
  }
  next->manager.registerObjects(raw);
  next->manager.setup();
  if (options_.selfCollision) next->selfPairs = robot_.selfCollisionPairs(scene.allowedCollisions);
  next->allowed = allowedObstacleContacts(robot_, scene);
  placeFixedShapes(*next);
  // Clearance bounds know no clouds: motions among them are checked state by state.
  if (options_.proveMotionsFree && next->clouds.empty()) {
    buildClearance(*next, scene);
    const auto obstaclePairs = std::ranges::count_if(
        next->clearance.pairs, [](const auto& pair) { return !pair.selfPair; });
    next->statesProven = obstaclePairs <= kMaxProvenStatePairs && !next->fixedContact;
  }
  obstacles_.set(std::move(next));
}

FclChecker::Cloud FclChecker::placeCloud(const PointCloud& cloud, const Eigen::Isometry3d& pose,
                                         const Eigen::Isometry3d& robotBase) const {
  // Balls farther from the robot's base than any point of the robot can reach are dropped.
  const double reach = geometry_->reach + cloud.radius;
  const Eigen::Vector3d base = robotBase.translation();
  std::vector<Eigen::Vector3d> world;
  world.reserve(cloud.cloud->points.size());
  for (const Eigen::Vector3d& p : cloud.cloud->points) {
    const Eigen::Vector3d w = pose * p;
    if ((w - base).squaredNorm() <= reach * reach) world.push_back(w);
  }
  Cloud placed;
  // Cells of a few balls' width: a link's box then spans a few cells a side, each holding a
  // few dozen points of a sensed surface (docs/geometry.md, "Point clouds").
  placed.grid = CloudGrid(world, std::max(4 * cloud.radius, 0.05));
  placed.radius = cloud.radius;
  placed.ball = std::make_shared<fcl::Sphered>(cloud.radius);
  return placed;
}

bool FclChecker::touchesCloud(const Cloud& cloud, std::size_t shape,
                              const fcl::CollisionObjectd& object) const {
  const fcl::AABBd& box = object.getAABB();
  const Eigen::AlignedBox3d near(box.min_.array() - cloud.radius, box.max_.array() + cloud.radius);
  const Eigen::Isometry3d toLocal = object.getTransform().inverse(Eigen::Isometry);
  const EnclosingVolume& volume = geometry_->volumes[shape];
  const bool mesh = geometry_->meshes[shape] != 0;
  const auto cellNear = [&](const Eigen::Vector3d& centre, double halfDiagonal) {
    return volume.distanceFrom(toLocal * centre) <= cloud.radius + halfDiagonal;
  };
  return cloud.grid.anyInBox(near, cellNear, [&](const Eigen::Vector3d& p) {
    if (!near.contains(p) || volume.distanceFrom(toLocal * p) > cloud.radius) return false;
    if (!mesh) return true;  // the distance is exact for a primitive
    const fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    fcl::collide(cloud.ball.get(), fcl::Transform3d(Eigen::Translation3d(p)),
                 geometry_->shapes[shape].collision.get(), object.getTransform(), request, result);
    return result.isCollision();
  });
}

double FclChecker::cloudDistance(const Cloud& cloud, std::size_t shape,
                                 const fcl::CollisionObjectd& object) const {
  if (cloud.grid.empty()) return std::numeric_limits<double>::infinity();
  if (geometry_->meshes[shape] != 0) {
    const fcl::DistanceRequestd request;
    fcl::DistanceResultd result;
    fcl::distance(geometry_->shapes[shape].distance.get(), object.getTransform(),
                  &cloud.pointHierarchy(), fcl::Transform3d::Identity(), request, result);
    return std::max(result.min_distance - cloud.radius, 0.0);
  }
  // A primitive's distance from a point is exact in closed form: the balls in boxes about the
  // shape that grow until one is nearer than any outside the box can be.
  const fcl::AABBd& box = object.getAABB();
  const Eigen::Isometry3d toLocal = object.getTransform().inverse(Eigen::Isometry);
  const EnclosingVolume& volume = geometry_->volumes[shape];
  const double whole = cloud.grid.bounds().sizes().norm() + box.size();
  for (double margin = cloud.grid.cell();; margin *= 2) {
    const Eigen::AlignedBox3d near(box.min_.array() - margin - cloud.radius,
                                   box.max_.array() + margin + cloud.radius);
    double best = std::numeric_limits<double>::infinity();
    cloud.grid.anyInBox(near, [&](const Eigen::Vector3d& p) {
      best = std::min(best, std::max(volume.distanceFrom(toLocal * p) - cloud.radius, 0.0));
      return best == 0;
    });
    if (best <= margin || margin > whole) return best;
  }
}

std::size_t FclChecker::selfPairTableCount() const {
  return geometry_->selfTables ? geometry_->selfTables->size() : 0;
}

/// Most nodes of one self-pair table (0.2 MB of floats; each costs an FCL distance to build: the
/// mesh Panda's four tables at 7 mm of slack took 11 s on one core, at 5 mm three of them needed
/// more). Tables kept in a cache depend on it: change pipeline/self_pair_tables.cpp's
/// kTablesVersion with it.
constexpr std::size_t kSelfTableNodes = 50000;

Eigen::VectorXd FclChecker::selfPairLevers(const Geometry& geometry, std::size_t a,
                                           std::size_t b) const {
  // Two links move apart only by the joints between them and the link they both hang from.
  const int from = commonAncestor(robot_, robot_.shapes()[a].link, robot_.shapes()[b].link);
  return shapeLevers(robot_, a, (*geometry.balls)[a].balls, from) +
         shapeLevers(robot_, b, (*geometry.balls)[b].balls, from);
}

std::shared_ptr<const std::vector<SelfPairTable>> FclChecker::selfPairTables() const {
  return geometry_->selfTables;
}

std::shared_ptr<const std::vector<SelfPairTable>> FclChecker::tabulateSelfPairs(
    const Geometry& geometry) const {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (const auto& shapes : robot_.selfCollisionPairs({})) {
    // Primitives' pairs need none: FCL's distance of two primitives costs as much as a lookup.
    if (geometry.meshes[shapes.first] != 0 || geometry.meshes[shapes.second] != 0)
      pairs.push_back(shapes);
  }
  // Each table costs thousands of FCL mesh distances (seconds on the mesh Panda): a pair per chunk,
  // on every core, each with kinematics of its own.
  std::vector<std::optional<SelfPairTable>> built(pairs.size());
  forEachChunk(pairs.size(), 1, 0, [&](std::size_t i, std::size_t) {
    const std::size_t a = pairs[i].first, b = pairs[i].second;
    KinematicsData kinematics = makeKinematicsData(robot_);
    const auto distance = [&](const double* q) {
      forwardKinematics(robot_, q, kinematics);
      fcl::DistanceRequestd request;
      fcl::DistanceResultd result;
      fcl::distance(geometry.shapes[a].distance.get(), toFcl(shapePose(robot_, kinematics, a)),
                    geometry.shapes[b].distance.get(), toFcl(shapePose(robot_, kinematics, b)),
                    request, result);
      return result.min_distance;
    };
    built[i] = tabulateSelfPair(a, b, selfPairLevers(geometry, a, b), robot_.limits(),
                                options_.selfPairSlack, kSelfTableNodes, distance);
  });
  auto tables = std::make_shared<std::vector<SelfPairTable>>();
  for (auto& table : built) {
    if (table) tables->push_back(std::move(*table));
  }
  return tables;
}

void FclChecker::buildClearance(Obstacles& world, const Scene& scene) const {
  const Geometry& geometry = *geometry_;
  ClearanceModel& model = world.clearance;
  model.balls = geometry.balls;
  model.movers = geometry.movers;
  for (const Obstacle& o : scene.obstacles()) model.obstacles.emplace_back(o.shape, o.pose);
  const std::size_t obstacles = world.objects.size();
  for (const std::size_t s : geometry.moving) {
    for (std::size_t o = 0; o < obstacles; ++o) {
      if (!world.allowed.empty() && world.allowed[s * obstacles + o] != 0) continue;
      ClearancePair pair{s, o, false, geometry.levers[s],
                         primitives(robot_.shapes()[s].shape, scene.obstacles()[o].shape)};
      pair.shapeMovers = static_cast<std::uint32_t>((*geometry.movers)[s].size());
      model.pairs.push_back(std::move(pair));
    }
  }
  model.selfTables = geometry.selfTables;
  for (const auto& [a, b] : world.movingSelfPairs) {
    ClearancePair pair{a, b, true, selfPairLevers(geometry, a, b),
                       primitives(robot_.shapes()[a].shape, robot_.shapes()[b].shape)};
    // Their movers below the link both hang from, the first of each one's.
    const int from = commonAncestor(robot_, robot_.shapes()[a].link, robot_.shapes()[b].link);
    pair.shapeMovers = static_cast<std::uint32_t>(
        shapeMovers(robot_, a, {(*geometry.balls)[a].whole}, from).size());
    pair.otherMovers = static_cast<std::uint32_t>(
        shapeMovers(robot_, b, {(*geometry.balls)[b].whole}, from).size());
    if (geometry.selfTables) {
      for (const SelfPairTable& t : *geometry.selfTables) {
        if ((t.shapeA == a && t.shapeB == b) || (t.shapeA == b && t.shapeB == a)) pair.table = &t;
      }
    }
    model.pairs.push_back(std::move(pair));
  }
}

void FclChecker::placeFixedShapes(Obstacles& world) const {
  const Geometry& geometry = *geometry_;
  const KinematicsData kinematics = kinematicsAtZero(robot_, world.robotBase);
  world.fixedObjects.resize(geometry.shapes.size());
  {
    const std::lock_guard lock(objectsOfRobotGeometry_);
    for (std::size_t s = 0; s < geometry.shapes.size(); ++s) {
      if (geometry.moves[s] != 0) continue;
      world.fixedObjects[s] = std::make_unique<fcl::CollisionObjectd>(
          geometry.shapes[s].collision, toFcl(shapePose(robot_, kinematics, s)));
      world.fixedObjects[s]->computeAABB();
    }
  }
  for (std::size_t s = 0; s < geometry.shapes.size() && !world.fixedContact; ++s) {
    if (geometry.moves[s] != 0) continue;
    CollideData data;
    if (!world.allowed.empty()) data.allowed = world.allowed.data() + s * world.objects.size();
    world.manager.collide(world.fixedObjects[s].get(), &data, collideCallback);
    if (data.hit != nullptr)
      world.fixedContact =
          Contact{robot_.shapeLinkName(s), world.names[obstacleIndex(data.hit)], false};
    if (const Cloud* cloud = touchedCloud(world, s, *world.fixedObjects[s]);
        cloud != nullptr && !world.fixedContact)
      world.fixedContact = Contact{robot_.shapeLinkName(s), world.names[cloud->obstacle], false};
  }
  for (const auto& [a, b] : world.selfPairs) {
    if (geometry.moves[a] != 0 || geometry.moves[b] != 0) {
      world.movingSelfPairs.emplace_back(a, b);
    } else if (!world.fixedContact && shapesTouch(*world.fixedObjects[a], *world.fixedObjects[b])) {
      world.fixedContact = Contact{robot_.shapeLinkName(a), robot_.shapeLinkName(b), true};
    }
  }
}

// Forward kinematics, then every robot shape that moves placed at its pose with its AABB updated.
void FclChecker::placeRobot(Scratch& scratch, const Eigen::Isometry3d& base,
                            const double* q) const {
  forwardKinematics(robot_, q, scratch.kinematics, base);
  for (const std::size_t s : geometry_->moving)
    placeObject(*scratch.robotObjects[s], shapePose(robot_, scratch.kinematics, s));
}

const FclChecker::Cloud* FclChecker::touchedCloud(const Obstacles& world, std::size_t shape,
                                                  const fcl::CollisionObjectd& object) const {
  for (const Cloud& cloud : world.clouds) {
    if (!world.allowed.empty() && world.allowed[shape * world.objects.size() + cloud.obstacle] != 0)
      continue;
    if (touchesCloud(cloud, shape, object)) return &cloud;
  }
  return nullptr;
}

std::optional<Contact> FclChecker::collide(const Obstacles& world, Scratch& scratch,
                                           const double* q, bool wantContact) const {
  if (world.fixedContact) return wantContact ? world.fixedContact : Contact{};
  placeRobot(scratch, world.robotBase, q);
  for (const std::size_t s : geometry_->moving) {
    CollideData data;
    if (!world.allowed.empty()) data.allowed = world.allowed.data() + s * world.objects.size();
    world.manager.collide(scratch.robotObjects[s].get(), &data, collideCallback);
    if (data.hit != nullptr) {
      if (!wantContact) return Contact{};
      return Contact{robot_.shapeLinkName(s), world.names[obstacleIndex(data.hit)], false};
    }
    if (const Cloud* cloud = touchedCloud(world, s, *scratch.robotObjects[s])) {
      if (!wantContact) return Contact{};
      return Contact{robot_.shapeLinkName(s), world.names[cloud->obstacle], false};
    }
  }
  for (const auto& [a, b] : world.movingSelfPairs) {
    if (shapesTouch(world.robotObject(scratch, a), world.robotObject(scratch, b)))
      return Contact{robot_.shapeLinkName(a), robot_.shapeLinkName(b), true};
  }
  return std::nullopt;
}

std::vector<Contact> FclChecker::selfContacts(std::span<const double> q) const {
  checkConfiguration(q, dof());
  const std::shared_ptr<const Obstacles> world = obstacles_.get();
  auto scratch = scratch_.lease();
  placeRobot(*scratch, world->robotBase, q.data());
  std::vector<Contact> contacts;
  std::vector<std::pair<int, int>> linkPairs;  // a link with several shapes counts once
  for (const auto& [a, b] : world->selfPairs) {
    const std::pair<int, int> links = std::minmax(robot_.shapes()[a].link, robot_.shapes()[b].link);
    if (std::find(linkPairs.begin(), linkPairs.end(), links) != linkPairs.end()) continue;
    if (!shapesTouch(world->robotObject(*scratch, a), world->robotObject(*scratch, b))) continue;
    linkPairs.push_back(links);
    contacts.push_back({robot_.links()[static_cast<std::size_t>(links.first)].name,
                        robot_.links()[static_cast<std::size_t>(links.second)].name, true});
  }
  return contacts;
}

bool FclChecker::check(const double* q) const {
  return checkFirst(q, 1) == 0;
}

bool FclChecker::boundsStateChecks() const {
  const std::shared_ptr<const Obstacles> world = obstacles_.get();
  return world->statesProven;
}

bool FclChecker::collides(const Obstacles& world, Scratch& scratch, const double* q) const {
  if (!world.statesProven) return collide(world, scratch, q, false).has_value();
  return certifiedStateCheck(world.clearance, exactPairs(world, scratch), scratch.motion->balls, q);
}

// One read of the world and one scratch lease for the whole run: with two threads verifying a
// path, locking both for every state cost a third of the parallel speed-up.
std::size_t FclChecker::checkFirst(const double* q, std::size_t n) const {
  const std::shared_ptr<const Obstacles> world = obstacles_.get();
  auto scratch = scratch_.lease();
  for (std::size_t i = 0; i < n; ++i) {
    if (collides(*world, *scratch, q + i * robot_.dof())) return i;
  }
  return n;
}

void FclChecker::checkEach(const double* q, std::size_t n, std::uint8_t* out) const {
  const std::shared_ptr<const Obstacles> world = obstacles_.get();
  auto scratch = scratch_.lease();
  for (std::size_t i = 0; i < n; ++i) out[i] = collides(*world, *scratch, q + i * robot_.dof());
}

bool FclChecker::leversHold(const double* from, const double* to) const {
  return std::ranges::all_of(geometry_->prismatic, [&](const auto& joint) {
    const auto& [k, lower, upper] = joint;
    return from[k] >= lower && from[k] <= upper && to[k] >= lower && to[k] <= upper;
  });
}

const ExactPairCheck& FclChecker::exactPairs(const Obstacles& world, Scratch& scratch) const {
  scratch.world = &world;
  return scratch.pairs;
}

ExactPairCheck FclChecker::exactPairCheck(Scratch& scratch) const {
  ExactPairCheck exact;
  exact.place = [this, &scratch](const double* q, std::vector<Eigen::Isometry3d>& poses) {
    forwardKinematics(robot_, q, scratch.kinematics, scratch.world->robotBase);
    ++scratch.placing;
    poses.resize(robot_.shapes().size());
    for (std::size_t s = 0; s < poses.size(); ++s)
      poses[s] = shapePose(robot_, scratch.kinematics, s);
  };
  exact.axes = [this, &scratch](std::vector<JointAxis>& axes) {
    const std::vector<Joint>& joints = robot_.joints();
    axes.resize(joints.size());
    for (std::size_t j = 0; j < joints.size(); ++j) {
      if (!joints[j].movable()) continue;
      const Eigen::Isometry3d& child =
          scratch.kinematics.linkPoses[static_cast<std::size_t>(joints[j].child)];
      axes[j] = {child.translation(), child.linear() * joints[j].axis};
    }
  };
  // Robot shape `s` as FCL's object, placed on first use for the configuration last placed (most
  // shapes are never asked about: their bounds keep them apart).
  const auto object = [this, &scratch](std::size_t s) -> const fcl::CollisionObjectd& {
    if (!scratch.world->fixedObjects[s] && scratch.placedAt[s] != scratch.placing) {
      placeObject(*scratch.robotObjects[s], shapePose(robot_, scratch.kinematics, s));
      scratch.placedAt[s] = scratch.placing;
    }
    return scratch.world->robotObject(scratch, s);
  };
  // As the dense check decides a pair: boxes first, then FCL's narrow phase, a self pair in the
  // order it is listed in, an obstacle pair as obstacleTouches asks it.
  exact.touches = [&scratch, object](const ClearancePair& pair) {
    if (pair.selfPair) return shapesTouch(object(pair.shape), object(pair.other));
    return obstacleTouches(*scratch.world->objects[pair.other], object(pair.shape));
  };
  exact.distance = [this, &scratch, object](const ClearancePair& pair) {
    const Obstacles& world = *scratch.world;
    const fcl::DistanceRequestd request;
    fcl::DistanceResultd result;
    const fcl::CollisionObjectd& a = object(pair.shape);
    const fcl::CollisionGeometryd* shape = geometry_->shapes[pair.shape].distance.get();
    if (pair.selfPair) {
      fcl::distance(shape, a.getTransform(), geometry_->shapes[pair.other].distance.get(),
                    object(pair.other).getTransform(), request, result);
    } else {
      fcl::distance(shape, a.getTransform(), world.distanceShapes[pair.other].get(),
                    world.objects[pair.other]->getTransform(), request, result);
    }
    return result.min_distance;
  };
  return exact;
}

CollisionChecker::MotionCheck FclChecker::checkMotion(const double* from, const double* to,
                                                      std::size_t segments) const {
  const std::shared_ptr<const Obstacles> world = obstacles_.get();
  if (!options_.proveMotionsFree || !leversHold(from, to) || !world->clouds.empty())
    return checkMotionStateByState(from, to, segments);
  if (world->fixedContact) return {segments, 1};  // every state collides; `to` is looked at first
  auto scratch = scratch_.lease();
  if (scratch->motionGeneration != world->generation) {
    scratch->motion->forgetEnd();
    scratch->motionGeneration = world->generation;
  }
  const CertifiedMotion answer =
      certifiedMotionCheck(world->clearance, exactPairs(*world, *scratch), from, to, robot_.dof(),
                           segments, *scratch->motion);
  return {answer.collidingState, answer.statesPlaced};
}

std::optional<Contact> FclChecker::contactAt(const double* q) const {
  const std::shared_ptr<const Obstacles> world = obstacles_.get();
  auto scratch = scratch_.lease();
  return collide(*world, *scratch, q, true);
}

double FclChecker::distanceAt(const double* q) const {
  const std::shared_ptr<const Obstacles> world = obstacles_.get();
  auto scratch = scratch_.lease();
  if (collide(*world, *scratch, q, false)) return 0;  // the robot is placed
  double best = std::numeric_limits<double>::infinity();
  fcl::DistanceRequestd request;
  for (std::size_t s = 0; s < robot_.shapes().size(); ++s) {
    const fcl::Transform3d& pose = world->robotObject(*scratch, s).getTransform();
    const fcl::CollisionGeometryd* shape = geometry_->shapes[s].distance.get();
    for (std::size_t o = 0; o < world->objects.size(); ++o) {
      if (!world->allowed.empty() && world->allowed[s * world->objects.size() + o] != 0) continue;
      if (!world->objects[o]) continue;  // a cloud: below
      fcl::DistanceResultd result;
      fcl::distance(shape, pose, world->distanceShapes[o].get(), world->objects[o]->getTransform(),
                    request, result);
      best = std::min(best, std::max(0.0, result.min_distance));
    }
    for (const Cloud& cloud : world->clouds) {
      if (!world->allowed.empty() &&
          world->allowed[s * world->objects.size() + cloud.obstacle] != 0)
        continue;
      best = std::min(best, cloudDistance(cloud, s, world->robotObject(*scratch, s)));
    }
  }
  return best;
}

}  // namespace fastron
