// FCL and GJK checkers: hand-computed contacts for every shape pair, agreement between the two,
// self-collision, contacts, distance, padding and scene updates.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/gjk_checker.h"
#include "fastron/geometry/kinematics.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/proxy/labelling.h"
#include "temp_dir.h"

namespace fastron {
namespace {

#ifdef FASTRON_SANITIZED
constexpr std::size_t kAgreementSamples = 10'000;  // sanitizers slow checks down ~10 times
#else
constexpr std::size_t kAgreementSamples = 100'000;
#endif

std::shared_ptr<const TriangleMesh> cubeMesh(double side) {
  auto mesh = std::make_shared<TriangleMesh>();
  const double h = side / 2;
  for (int i = 0; i < 8; ++i)
    mesh->vertices.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
  const int faces[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                            {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  for (const auto& f : faces) mesh->triangles.emplace_back(f[0], f[1], f[2]);
  mesh->source = "cube";
  return mesh;
}

// A body that slides along world x: q is its centre's x coordinate.
Robot slider(const Shape& shape) {
  Joint joint;
  joint.name = "x";
  joint.type = JointType::Prismatic;
  joint.parent = 0;
  joint.child = 1;
  joint.axis = Eigen::Vector3d::UnitX();
  joint.lower = -5;
  joint.upper = 5;
  return Robot("slider", {{"base", -1}, {"body", -1}}, {joint},
               {{1, Eigen::Isometry3d::Identity(), shape}});
}

struct NamedShape {
  std::string name;
  Shape shape;
};

// Every shape has half-width 0.1 along x, so two of them touch at q = 0.2.
std::vector<NamedShape> shapesOfHalfWidthOneTenth() {
  return {{"box", Box{Eigen::Vector3d(0.2, 0.3, 0.4)}},
          {"sphere", Sphere{0.1}},
          {"cylinder", Cylinder{0.1, 0.3}},
          {"capsule", Capsule{0.1, 0.3}},
          {"mesh", Mesh{cubeMesh(0.2)}}};
}

TEST(Checkers, EveryShapePairTouchesWhereHandComputed) {
  const double gap = 0.005;
  std::size_t pairs = 0;
  for (const auto& robotShape : shapesOfHalfWidthOneTenth()) {
    for (const auto& obstacleShape : shapesOfHalfWidthOneTenth()) {
      Scene scene;
      scene.add({"obstacle", obstacleShape.shape, Eigen::Isometry3d::Identity(), std::nullopt});
      const FclChecker fcl(slider(robotShape.shape), scene);
      const GjkChecker gjk(slider(robotShape.shape), scene);
      for (const double side : {1.0, -1.0}) {
        const std::vector<double> apart{side * (0.2 + gap)}, overlapping{side * (0.2 - gap)},
            centred{0.0};
        const std::string pair = robotShape.name + " vs " + obstacleShape.name;
        EXPECT_FALSE(fcl.inCollision(apart)) << "FCL " << pair;
        EXPECT_FALSE(gjk.inCollision(apart)) << "GJK " << pair;
        // Meshes are checked on an OBB hierarchy and measured on an OBBRSS one.
        EXPECT_NEAR(fcl.distance(apart), gap, 1e-4) << "FCL " << pair;  // libccd: 8e-6
        EXPECT_TRUE(fcl.inCollision(overlapping)) << "FCL " << pair;
        EXPECT_TRUE(gjk.inCollision(overlapping)) << "GJK " << pair;
        EXPECT_TRUE(gjk.inCollision(centred)) << "GJK " << pair;
      }
      ++pairs;
    }
  }
  EXPECT_EQ(pairs, 25u);
  // A mesh wholly inside a box touches none of its faces, and still collides: FCL tests the
  // mesh's triangles against the box as a solid.
  Scene big;
  big.add({"big", Box{Eigen::Vector3d(1, 1, 1)}, Eigen::Isometry3d::Identity(), std::nullopt});
  EXPECT_TRUE(FclChecker(slider(Mesh{cubeMesh(0.2)}), big).inCollision(std::vector<double>{0.1}));
}

TEST(Checkers, RotatedObstaclesAndEnds) {
  // A box turned 45 degrees about z reaches 0.1 * sqrt(2) along x.
  Scene turned;
  turned.add({"box", Box{Eigen::Vector3d(0.2, 0.2, 0.2)},
              makePose({0, 0, 0}, {0, 0, std::numbers::pi / 4}), std::nullopt});
  const double corner = 0.1 * std::sqrt(2.0) + 0.1;
  for (const CollisionChecker* c : std::initializer_list<const CollisionChecker*>{
           new FclChecker(slider(Sphere{0.1}), turned),
           new GjkChecker(slider(Sphere{0.1}), turned)}) {
    EXPECT_FALSE(c->inCollision(std::vector<double>{corner + 0.005})) << c->name();
    EXPECT_TRUE(c->inCollision(std::vector<double>{corner - 0.005})) << c->name();
    delete c;
  }
  // A capsule lying along x reaches r + l/2 = 0.25 from its centre; a cylinder 0.15.
  Scene lying;
  lying.add(
      {"pill", Capsule{0.1, 0.3}, makePose({0, 0, 0}, {0, std::numbers::pi / 2, 0}), std::nullopt});
  lying.add(
      {"can", Cylinder{0.1, 0.3}, makePose({0, 3, 0}, {0, std::numbers::pi / 2, 0}), std::nullopt});
  const FclChecker fcl(slider(Sphere{0.05}), lying);
  const GjkChecker gjk(slider(Sphere{0.05}), lying);
  EXPECT_FALSE(fcl.inCollision(std::vector<double>{0.305}));
  EXPECT_TRUE(fcl.inCollision(std::vector<double>{0.295}));
  EXPECT_FALSE(gjk.inCollision(std::vector<double>{0.305}));
  EXPECT_TRUE(gjk.inCollision(std::vector<double>{0.295}));
}

// A scene of primitives around Baxter's right arm: FCL and GJK see the same geometry, so they
// must agree except within numerical tolerance of a contact.
Scene baxterPrimitives() {
  Scene scene;
  scene.add({"box", Box{Eigen::Vector3d(0.2, 0.2, 0.2)},
             makePose({0.6, -0.6, 0.2}, {0.3, 0.2, 0.5}), std::nullopt});
  scene.add({"ball", Sphere{0.12}, makePose({0.4, -0.9, 0.5}), std::nullopt});
  scene.add({"can", Cylinder{0.08, 0.4}, makePose({0.8, -0.3, 0.0}, {0.5, 0, 0}), std::nullopt});
  scene.add({"pill", Capsule{0.06, 0.3}, makePose({0.3, -0.5, -0.2}, {0, 1.2, 0}), std::nullopt});
  scene.add({"cube_mesh", Mesh{cubeMesh(0.15)}, makePose({0.9, -0.8, 0.4}), std::nullopt});
  return scene;
}

TEST(Checkers, AGrownSceneCollidesWhereverTheSceneDoesAndMore) {
  const Robot baxter = loadRobot("baxter");
  const Scene scene = baxterPrimitives();
  const Scene grown = scene.grown(0.02);
  EXPECT_TRUE(
      std::get<Box>(grown.obstacle("box").shape).size.isApprox(Eigen::Vector3d::Constant(0.24)));
  EXPECT_DOUBLE_EQ(std::get<Sphere>(grown.obstacle("ball").shape).radius, 0.14);
  EXPECT_DOUBLE_EQ(std::get<Capsule>(grown.obstacle("pill").shape).radius, 0.08);
  EXPECT_EQ(std::get<Mesh>(grown.obstacle("cube_mesh").shape).mesh,
            std::get<Mesh>(scene.obstacle("cube_mesh").shape).mesh);  // meshes stay
  EXPECT_TRUE(grown.obstacle("can").pose.isApprox(scene.obstacle("can").pose));
  Rng rng(8);
  const Configurations q = uniformConfigurations(baxter.limits(), 2000, rng);
  const Labels exact = labelConfigurations(FclChecker(baxter, scene), q);
  const Labels roomy = labelConfigurations(FclChecker(baxter, grown), q);
  std::size_t more = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    if (exact[i] > 0) {
      EXPECT_GT(roomy[i], 0) << "configuration " << i;
    }
    more += exact[i] < 0 && roomy[i] > 0;
  }
  EXPECT_GT(more, 0u);
  EXPECT_THROW((void)scene.grown(-0.01), InvalidArgument);
  EXPECT_THROW((void)scene.grown(std::nan("")), InvalidArgument);
}

TEST(Checkers, FclAndGjkAgreeOnPrimitiveScenes) {
  const Robot baxter = loadRobot("baxter");
  const Scene scene = baxterPrimitives();
  const FclChecker fcl(baxter, scene);
  const GjkChecker gjk(baxter, scene);
  Rng rng(5);
  const Configurations q = uniformConfigurations(baxter.limits(), kAgreementSamples, rng);
  const Labels a = labelConfigurations(fcl, q), b = labelConfigurations(gjk, q);
  std::size_t disagreements = 0, collisions = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    disagreements += a[i] != b[i];
    collisions += a[i] > 0;
  }
  RecordProperty("disagreements", static_cast<int>(disagreements));
  RecordProperty("configurations", static_cast<int>(a.size()));
  std::cout << "FCL vs GJK on " << a.size() << " Baxter configurations: " << collisions
            << " in collision, " << disagreements << " disagreements\n";
  EXPECT_GT(collisions, a.size() / 20);  // the scene is not trivially free
  // Ties at contact, within numerical tolerance: a few in 10^4 (5 in 10^5 on the last Release run).
  EXPECT_LE(disagreements, 2 + a.size() / 5'000);
}

// A run of configurations answered at once (inCollisionEach: one read of the world, one
// scratch; the labelling's path) answers each as a check of its own does, and counts each.
TEST(Checkers, ARunAnsweredAtOnceAnswersEachAsAlone) {
  const Robot baxter = loadRobot("baxter");
  const Scene scene = baxterPrimitives();
  const FclChecker fcl(baxter, scene);
  const GjkChecker gjk(baxter, scene);
  Rng rng(8);
  const Configurations q = uniformConfigurations(baxter.limits(), 500, rng);
  for (const CollisionChecker* checker :
       std::initializer_list<const CollisionChecker*>{&fcl, &gjk}) {
    SCOPED_TRACE(checker->name());
    const std::vector<std::uint8_t> run = checker->inCollisionBatch(q);
    EXPECT_EQ(checker->callCount(), 500u);
    std::size_t collisions = 0;
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      const bool alone = checker->inCollision({q.row(i).data(), baxter.dof()});
      EXPECT_EQ(run[static_cast<std::size_t>(i)] != 0, alone) << "row " << i;
      collisions += alone;
    }
    EXPECT_GT(collisions, 25u);  // both answers occur
    EXPECT_LT(collisions, 475u);
  }
  Configurations bad = q.topRows(3);
  bad(2, 4) = std::nan("");
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] { fcl.inCollisionBatch(bad); }),
              ::testing::HasSubstr("configuration 2"));
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] { gjk.inCollisionBatch(q.leftCols(6)); }),
              ::testing::HasSubstr("6 columns"));
}

TEST(Checkers, SelfCollisionFindsTheArmHittingTheBody) {
  const Robot baxter = loadRobot("baxter");
  const Scene empty;
  const FclChecker withoutSelf(baxter, empty);
  const FclChecker fcl(baxter, empty, {.selfCollision = true});
  const GjkChecker gjk(baxter, empty, {.selfCollision = true});
  const std::vector<double> zero(7, 0.0);
  EXPECT_FALSE(fcl.inCollision(zero));
  Rng rng(6);
  const Configurations q = uniformConfigurations(baxter.limits(), 3000, rng);
  std::size_t selfHits = 0, disagreements = 0;
  const AllowedCollisionMatrix adjacent = baxter.adjacentLinks();
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const std::span<const double> c(q.row(i).data(), 7);
    EXPECT_FALSE(withoutSelf.inCollision(c));  // nothing else in the scene
    const auto contact = fcl.firstContact(c);
    disagreements += contact.has_value() != gjk.inCollision(c);
    if (!contact) continue;
    ++selfHits;
    EXPECT_TRUE(contact->selfCollision);
    EXPECT_FALSE(adjacent.allowed(contact->robotLink, contact->other))
        << contact->robotLink << " " << contact->other;
  }
  EXPECT_GT(selfHits, 30u);
  EXPECT_LE(disagreements, 3u);
  // Allowing every pair of the scene's matrix silences them.
  Scene allowAll;
  for (const auto& a : baxter.links()) {
    for (const auto& b : baxter.links()) allowAll.allowedCollisions.allow(a.name, b.name);
  }
  const FclChecker permissive(baxter, allowAll, {.selfCollision = true});
  for (Eigen::Index i = 0; i < 200; ++i) EXPECT_FALSE(permissive.inCollision({q.row(i).data(), 7}));
}

// Shapes that no configuration moves (Baxter's base, head and torso) are checked once per scene:
// an obstacle on one of them makes every configuration collide, in both checkers, until the scene
// allows the pair or moves the obstacle away.
TEST(Checkers, AnObstacleOnAShapeThatNeverMovesCollidesWithEveryConfiguration) {
  const Robot baxter = loadRobot("baxter");
  KinematicsData kinematics = makeKinematicsData(baxter);
  const std::vector<double> zero(7, 0.0);
  forwardKinematics(baxter, zero.data(), kinematics);
  const auto torso = static_cast<std::size_t>(
      std::find_if(baxter.shapes().begin(), baxter.shapes().end(),
                   [&](const LinkShape& s) { return s.link == baxter.linkIndex("torso"); }) -
      baxter.shapes().begin());
  ASSERT_LT(torso, baxter.shapes().size());
  Scene scene;
  scene.add({"on_the_torso", Sphere{0.02},
             makePose(shapePose(baxter, kinematics, torso).translation()), std::nullopt});
  Rng rng(8);
  const Configurations q = uniformConfigurations(baxter.limits(), 200, rng);
  const auto collidingCount = [&](const CollisionChecker& checker) {
    std::size_t colliding = 0;
    for (Eigen::Index i = 0; i < q.rows(); ++i)
      colliding += checker.inCollision({q.row(i).data(), 7}) ? 1 : 0;
    return colliding;
  };
  for (const bool self : {false, true}) {
    FclChecker fcl(baxter, scene, {.selfCollision = self});
    const GjkChecker gjk(baxter, scene, {.selfCollision = self});
    EXPECT_EQ(collidingCount(fcl), 200u);
    EXPECT_EQ(collidingCount(gjk), 200u);
    const auto contact = fcl.firstContact({q.row(0).data(), 7});
    ASSERT_TRUE(contact.has_value());
    EXPECT_EQ(contact->robotLink, "torso");
    EXPECT_EQ(contact->other, "on_the_torso");
    EXPECT_EQ(fcl.distance({q.row(0).data(), 7}), 0.0);

    Scene moved = scene;
    moved.setPose("on_the_torso", makePose({5, 5, 5}));
    fcl.setScene(moved);
    EXPECT_EQ(collidingCount(fcl),
              collidingCount(GjkChecker(baxter, moved, {.selfCollision = self})));
    EXPECT_LT(collidingCount(fcl), 200u);
    EXPECT_GT(fcl.distance(zero), 1.0);  // the arm's own shapes are far from (5, 5, 5)
  }
  Scene allowed = scene;
  allowed.allowedCollisions.allow("on_the_torso", "torso");
  EXPECT_LT(collidingCount(FclChecker(baxter, allowed)), 200u);
  EXPECT_LT(collidingCount(GjkChecker(baxter, allowed)), 200u);
}

// Two shapes that no configuration moves can still be a self-collision pair: here a held joint
// turns the tip of a chain back onto its base (held joints, not fixed ones, join them, and the
// link between them has geometry, so the pair is not adjacent). Every configuration of the
// actuated slider then collides with the robot itself.
TEST(Checkers, TwoShapesThatNeverMoveCanTouchEachOther) {
  const auto joint = [](std::string name, JointType type, int parent, int child, double x) {
    Joint j;
    j.name = std::move(name);
    j.type = type;
    j.parent = parent;
    j.child = child;
    j.origin.translation() = Eigen::Vector3d(x, 0, 0);
    j.axis = type == JointType::Prismatic ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
    j.lower = -4;
    j.upper = 4;
    return j;
  };
  const Box cube{Eigen::Vector3d(0.2, 0.2, 0.2)};
  // base at 0, mid at x 1, tip 1 further along mid's x axis; the slider at z 2, clear of them.
  Joint slide = joint("slide", JointType::Prismatic, 0, 3, 0);
  slide.origin.translation() = Eigen::Vector3d(0, 0, 2);
  Robot robot("chain", {{"base", -1}, {"mid", -1}, {"tip", -1}, {"slider", -1}},
              {joint("bend", JointType::Revolute, 0, 1, 1),
               joint("fold", JointType::Revolute, 1, 2, 1), slide},
              {{0, Eigen::Isometry3d::Identity(), cube},
               {1, Eigen::Isometry3d::Identity(), cube},
               {2, Eigen::Isometry3d::Identity(), cube},
               {3, Eigen::Isometry3d::Identity(), cube}});
  robot.setActuatedJoints({"slide"});
  const std::vector<double> q{0.5};
  EXPECT_FALSE(FclChecker(robot, Scene{}, {.selfCollision = true}).inCollision(q));
  robot.setHeldPosition("bend", std::numbers::pi);  // the tip folds back onto the base
  const FclChecker fcl(robot, Scene{}, {.selfCollision = true});
  EXPECT_TRUE(fcl.inCollision(q));
  EXPECT_TRUE(GjkChecker(robot, Scene{}, {.selfCollision = true}).inCollision(q));
  const auto contact = fcl.firstContact(q);
  ASSERT_TRUE(contact.has_value());
  EXPECT_TRUE(contact->selfCollision);
  EXPECT_EQ(std::minmax(contact->robotLink, contact->other),
            std::minmax(std::string("base"), std::string("tip")));
  EXPECT_FALSE(FclChecker(robot, Scene{}).inCollision(q));  // without self-collision checks
}

TEST(Checkers, ContactNamesTheLinkAndTheObstacle) {
  const Robot baxter = loadRobot("baxter");
  Scene scene;
  scene.add({"on_the_hand", Sphere{0.05}, makePose({0.797, -0.992, 0.321}), std::nullopt});
  const FclChecker fcl(baxter, scene);
  const auto contact = fcl.firstContact(std::vector<double>(7, 0.0));
  ASSERT_TRUE(contact.has_value());
  EXPECT_THAT(contact->robotLink, ::testing::AnyOf("right_hand", "right_wrist"));
  EXPECT_EQ(contact->other, "on_the_hand");
  EXPECT_FALSE(contact->selfCollision);
}

TEST(Checkers, DistanceAndPadding) {
  const Robot rod = loadRobot("rod2");  // capsule from x = 0 to 0.5, radius 0.03, at q = 0
  Scene scene;
  scene.add({"ball", Sphere{0.1}, makePose({0.8, 0, 0}), std::nullopt});
  const FclChecker fcl(rod, scene);
  EXPECT_NEAR(fcl.distance(std::vector<double>{0, 0}), 0.8 - 0.1 - 0.53, 1e-4);
  EXPECT_EQ(fcl.distance(std::vector<double>{0, 0}) > 0,
            !fcl.inCollision(std::vector<double>{0, 0}));

  scene.setPose("ball", makePose({0.66, 0, 0}));  // 0.03 from the rod
  const FclChecker bare(rod, scene), padded(rod, scene, {.padding = 0.05});
  const GjkChecker gjkPadded(rod, scene, {.padding = 0.05});
  EXPECT_FALSE(bare.inCollision(std::vector<double>{0, 0}));
  EXPECT_TRUE(padded.inCollision(std::vector<double>{0, 0}));
  EXPECT_TRUE(gjkPadded.inCollision(std::vector<double>{0, 0}));
  EXPECT_EQ(bare.distance(std::vector<double>{0, 0.5}) > 0.03, true);
}

TEST(Checkers, AllowedRobotObstaclePairsMayTouch) {
  // A grasped object may touch the hand: the scene's allowed collision matrix names the pair.
  const Robot rod = loadRobot("rod2");
  const std::string link = rod.links()[static_cast<std::size_t>(rod.shapes()[0].link)].name;
  Scene scene;
  scene.add({"held", Sphere{0.1}, makePose({0.3, 0, 0}), std::nullopt});
  scene.add({"far", Sphere{0.1}, makePose({-2, 0, 0}), std::nullopt});
  const std::vector<double> q{0, 0};
  EXPECT_TRUE(FclChecker(rod, scene).inCollision(q));
  scene.allowedCollisions.allow("held", link);
  const FclChecker fcl(rod, scene);
  const GjkChecker gjk(rod, scene);
  EXPECT_FALSE(fcl.inCollision(q));
  EXPECT_FALSE(gjk.inCollision(q));
  EXPECT_GT(fcl.distance(q), 1.0);  // to the other obstacle only
  // Other obstacles still count.
  scene.setPose("far", makePose({0.2, 0.05, 0}));
  const FclChecker fclFar(rod, scene);
  EXPECT_TRUE(fclFar.inCollision(q));
  EXPECT_EQ(fclFar.firstContact(q)->other, "far");
  EXPECT_TRUE(GjkChecker(rod, scene).inCollision(q));
}

TEST(Checkers, SetSceneMovesTheObstacles) {
  const Robot rod = loadRobot("rod2");
  Scene scene;
  scene.add({"ball", Sphere{0.1}, makePose({0.3, 0, 0}), std::nullopt});
  FclChecker fcl(rod, scene);
  GjkChecker gjk(rod, scene);
  const std::vector<double> q{0, 0};
  EXPECT_TRUE(fcl.inCollision(q));
  EXPECT_TRUE(gjk.inCollision(q));
  scene.setPose("ball", makePose({0, 0.3, 0}));
  fcl.setScene(scene);
  gjk.setScene(scene);
  EXPECT_FALSE(fcl.inCollision(q));
  EXPECT_FALSE(gjk.inCollision(q));
  EXPECT_TRUE(fcl.inCollision(std::vector<double>{std::numbers::pi / 2, 0}));
  // The robot base moves the robot, not the obstacles.
  scene.robotBase = makePose({0, 0.3, 0});
  fcl.setScene(scene);
  EXPECT_TRUE(fcl.inCollision(q));
}

// A mesh obstacle's hierarchy is built once: moving the scene moves it, a second obstacle of the
// same mesh shares it, and only another mesh builds another.
TEST(Checkers, MovingAMeshObstacleKeepsItsHierarchy) {
  auto cube = std::make_shared<TriangleMesh>();
  for (int i = 0; i < 8; ++i) {
    cube->vertices.emplace_back((i & 1) ? 0.05 : -0.05, (i & 2) ? 0.05 : -0.05,
                                (i & 4) ? 0.05 : -0.05);
  }
  for (const auto& t : std::vector<Eigen::Vector3i>{{0, 1, 3},
                                                    {0, 3, 2},
                                                    {4, 6, 7},
                                                    {4, 7, 5},
                                                    {0, 4, 5},
                                                    {0, 5, 1},
                                                    {2, 3, 7},
                                                    {2, 7, 6},
                                                    {0, 2, 6},
                                                    {0, 6, 4},
                                                    {1, 5, 7},
                                                    {1, 7, 3}}) {
    cube->triangles.push_back(t);
  }
  const Robot rod = loadRobot("rod2");
  Scene scene;
  scene.add({"cube", Mesh{cube}, makePose({0.3, 0, 0}), std::nullopt});
  FclChecker fcl(rod, scene);
  const std::vector<double> q{0, 0};
  EXPECT_TRUE(fcl.inCollision(q));
  EXPECT_EQ(fcl.meshHierarchiesBuilt(), 1u);
  for (int step = 1; step <= 10; ++step) {
    scene.setPose("cube", makePose({0.3, 0.03 * step, 0}));
    fcl.setScene(scene);
  }
  EXPECT_FALSE(fcl.inCollision(q));  // moved 0.3 m aside
  scene.add({"twin", Mesh{cube}, makePose({0.3, 0, 0}), std::nullopt});
  fcl.setScene(scene);
  EXPECT_TRUE(fcl.inCollision(q));
  EXPECT_EQ(fcl.meshHierarchiesBuilt(), 1u);
  scene.add(
      {"other", Mesh{std::make_shared<TriangleMesh>(*cube)}, makePose({0, 0.5, 0}), std::nullopt});
  fcl.setScene(scene);
  EXPECT_EQ(fcl.meshHierarchiesBuilt(), 2u);
}

TEST(Checkers, RefuseBadConfigurationsAndOptions) {
  const Robot rod = loadRobot("rod2");
  const FclChecker fcl(rod, Scene{});
  const GjkChecker gjk(rod, Scene{});
  EXPECT_THROW(fcl.inCollision(std::vector<double>{0.0}), InvalidArgument);
  EXPECT_THROW(gjk.inCollision(std::vector<double>{0.0, std::nan("")}), InvalidArgument);
  EXPECT_THROW(fcl.firstContact(std::vector<double>{0, 0, 0}), InvalidArgument);
  EXPECT_THROW(FclChecker(slider(Mesh{cubeMesh(0.2)}), Scene{}, {.padding = 0.01}),
               InvalidArgument);
  EXPECT_THROW(FclChecker(rod, Scene{}, {.padding = -1}), InvalidArgument);
  EXPECT_EQ(fcl.callCount(), 0u);  // refused calls are not counted
}

}  // namespace
}  // namespace fastron
