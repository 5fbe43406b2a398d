// Scenes: obstacles, motions, the project's YAML and MoveIt's PlanningScene / MotionPlanRequest.

#include "fastron/geometry/scene.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fastron/core/error.h"
#include "fastron/geometry/moveit_writer.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/geometry/scene_file.h"
#include "temp_dir.h"

namespace fastron {
namespace {

using test::messageOf;
using ::testing::HasSubstr;

TEST(Scene, AddMoveRemove) {
  Scene scene;
  scene.add({"box", Box{Eigen::Vector3d(0.2, 0.2, 0.2)}, makePose({1, 0, 0}), std::nullopt});
  scene.add({"ball", Sphere{0.1}, makePose({0, 1, 0}), std::nullopt});
  scene.setPose("box", makePose({0, 0, 2}));
  EXPECT_EQ(scene.obstacle("box").pose.translation(), Eigen::Vector3d(0, 0, 2));
  scene.remove("ball");
  EXPECT_EQ(scene.size(), 1u);
  EXPECT_THROW(scene.remove("ball"), InvalidArgument);
  EXPECT_THROW(scene.add({"box", Sphere{1}, makePose({0, 0, 0}), std::nullopt}),
               InvalidArgument);  // name taken
  EXPECT_THROW(scene.add({"", Sphere{1}, makePose({0, 0, 0}), std::nullopt}), InvalidArgument);
  EXPECT_THROW(
      scene.add({"flat", Box{Eigen::Vector3d(0.2, 0, 0.2)}, makePose({0, 0, 0}), std::nullopt}),
      InvalidArgument);
  EXPECT_THROW(scene.add({"neg", Sphere{-1}, makePose({0, 0, 0}), std::nullopt}), InvalidArgument);
  EXPECT_THROW(scene.setPose("box", makePose({std::nan(""), 0, 0})), InvalidArgument);
}

TEST(Scene, RandomWalkStaysInItsBoundsWithStepsInRange) {
  Scene scene;
  RandomWalk walk{0.01, 0.04,
                  Eigen::AlignedBox3d(Eigen::Vector3d(0, -0.5, 0), Eigen::Vector3d(0.5, 0, 0.5)),
                  9};
  scene.add({"box", Box{Eigen::Vector3d::Constant(0.2)}, makePose({0.25, -0.25, 0.25}), walk});
  Eigen::Vector3d previous = scene.obstacle("box").pose.translation();
  for (int t = 0; t < 2000; ++t) {
    scene.step();
    const Eigen::Vector3d p = scene.obstacle("box").pose.translation();
    EXPECT_TRUE(walk.bounds.contains(p)) << p.transpose();
    EXPECT_LE((p - previous).norm(), 0.04 + 1e-12);  // a reflection only shortens a step
    previous = p;
  }
  // Same seed, same path.
  Scene again;
  again.add({"box", Box{Eigen::Vector3d::Constant(0.2)}, makePose({0.25, -0.25, 0.25}), walk});
  again.step(2000);
  EXPECT_EQ(again.obstacle("box").pose.translation(), previous);
}

TEST(Scene, CircularAndScriptedMotions) {
  Scene scene;
  scene.add({"c", Sphere{0.1}, makePose({0, 0, 0}),
             CircularPath{{1, 0, 0}, 0.5, Eigen::Vector3d::UnitZ(), 40, 0}});
  const double r0 = (scene.obstacle("c").pose.translation() - Eigen::Vector3d(1, 0, 0)).norm();
  EXPECT_NEAR(r0, 0.5, 1e-12);
  const Eigen::Vector3d start = scene.obstacle("c").pose.translation();
  scene.step(20);  // half a revolution: the opposite point
  EXPECT_LT(
      (scene.obstacle("c").pose.translation() - (2 * Eigen::Vector3d(1, 0, 0) - start)).norm(),
      1e-9);
  scene.step(20);
  EXPECT_LT((scene.obstacle("c").pose.translation() - start).norm(), 1e-9);

  Scene scripted;
  ScriptedPoses s{{0, 10},
                  {makePose({0, 0, 0}), makePose({1, 0, 0}, {0, 0, std::numbers::pi / 2})}};
  scripted.add({"s", Sphere{0.1}, makePose({0, 0, 0}), s});
  scripted.step(5);
  EXPECT_NEAR(scripted.obstacle("s").pose.translation().x(), 0.5, 1e-12);
  EXPECT_NEAR(Eigen::AngleAxisd(scripted.obstacle("s").pose.linear()).angle(), std::numbers::pi / 4,
              1e-9);
  scripted.step(100);
  EXPECT_NEAR(scripted.obstacle("s").pose.translation().x(), 1.0, 1e-12);
  EXPECT_THROW(scripted.add({"bad", Sphere{0.1}, makePose({0, 0, 0}),
                             ScriptedPoses{{2, 1}, {makePose({0, 0, 0}), makePose({0, 0, 0})}}}),
               InvalidArgument);
}

class SceneFiles : public test::TempDir {
 protected:
  std::string error(const std::string& yaml) {
    return messageOf<FileError>([&] { parseScene(yaml, "s.yaml", path("")); });
  }
};

TEST_F(SceneFiles, ReadsEveryShapeMotionAndTheRobotBase) {
  write("cube.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n");
  const Scene scene = parseScene(R"(
robot_base: {position: [0, 0, 0.5], rpy: [0, 0, 3.14159265]}
allowed_collisions: [[link_a, link_b]]
obstacles:
  - {name: box, shape: box, size: [0.2, 0.3, 0.4], position: [1, 0, 0], orientation: [0, 0, 0, 1]}
  - {name: ball, shape: sphere, radius: 0.1, position: [0, 1, 0]}
  - {name: can, shape: cylinder, radius: 0.05, length: 0.3}
  - {name: pill, shape: capsule, radius: 0.05, length: 0.2, rpy: [1.5707963, 0, 0]}
  - {name: tetra, shape: mesh, file: cube.obj, scale: [0.5, 0.5, 0.5]}
  - name: walker
    shape: box
    size: [0.2, 0.2, 0.2]
    position: [0.5, 0, 0.5]
    motion: {type: random_walk, step: [0.01, 0.04], bounds: [[0, -1, 0], [1, 1, 1]], seed: 4}
  - name: orbit
    shape: sphere
    radius: 0.05
    motion: {type: circle, centre: [0, 0, 1], radius: 0.2, period: 50}
  - name: script
    shape: sphere
    radius: 0.05
    motion:
      type: scripted
      keyframes: [{time: 0, position: [0, 0, 0]}, {time: 10, position: [1, 0, 0]}]
)",
                                 "s.yaml", path(""));
  EXPECT_EQ(scene.size(), 8u);
  EXPECT_NEAR(scene.robotBase.translation().z(), 0.5, 1e-12);
  EXPECT_TRUE(scene.allowedCollisions.allowed("link_b", "link_a"));
  EXPECT_EQ(std::get<Box>(scene.obstacle("box").shape).size, Eigen::Vector3d(0.2, 0.3, 0.4));
  EXPECT_EQ(std::get<Mesh>(scene.obstacle("tetra").shape).mesh->vertices[1],
            Eigen::Vector3d(0.5, 0, 0));
  EXPECT_TRUE(scene.obstacle("walker").motion.has_value());
  EXPECT_NEAR((scene.obstacle("orbit").pose.translation() - Eigen::Vector3d(0, 0, 1)).norm(), 0.2,
              1e-12);
}

TEST_F(SceneFiles, ErrorsNameTheLine) {
  EXPECT_THAT(error("obstacles:\n  - {name: a, shape: box, sise: [1, 1, 1]}\n"),
              HasSubstr("s.yaml:2: obstacle 'a': unknown key 'sise'"));
  EXPECT_THAT(error("obstacles:\n  - {name: a, shape: cone, radius: 1}\n"),
              HasSubstr("s.yaml:2: obstacle 'a': unknown shape 'cone'"));
  EXPECT_THAT(error("obstacles:\n  - {name: a, shape: box, size: [1, 1]}\n"),
              HasSubstr("s.yaml:2: obstacle 'a' size must be a list of 3 numbers"));
  EXPECT_THAT(error("obstacles:\n  - {name: a, shape: sphere, radius: -2}\n"),
              HasSubstr("s.yaml:2: obstacle 'a': sphere radius must be a finite positive number"));
  EXPECT_THAT(error("obstacles:\n  - {name: a, shape: sphere, radius: .nan}\n"),
              HasSubstr("s.yaml:2: obstacle 'a' radius is not finite"));
  EXPECT_THAT(
      error("obstacles:\n  - {name: a, shape: sphere, radius: 1,\n     position: [0, x, 0]}\n"),
      HasSubstr("s.yaml:3: obstacle 'a' position must be a number"));
  EXPECT_THAT(error("obstacles:\n  - {name: a, shape: sphere, radius: 1}\n  - {name: a, shape: "
                    "sphere, radius: 1}\n"),
              HasSubstr("s.yaml:3: two obstacles named 'a'"));
  EXPECT_THAT(error("obstacles:\n  - {name: a, shape: mesh, file: nowhere.stl}\n"),
              HasSubstr("s.yaml:2: obstacle 'a': "));
  EXPECT_THAT(
      error("obstacles:\n  - {name: a, shape: sphere, radius: 1, motion: {type: teleport}}\n"),
      HasSubstr("unknown motion type 'teleport'"));
  EXPECT_THAT(error("obstacles: [\n"), HasSubstr("malformed YAML"));
  EXPECT_THAT(error("obstacles:\n  - {name: [a, b], shape: sphere, radius: 1}\n"),
              HasSubstr("s.yaml:2: obstacle name must be a string"));
  EXPECT_THAT(
      error("obstacles:\n  - {name: a, shape: sphere, radius: 1, motion: {type: "
            "random_walk, step: [0.01, 0.02], bounds: [[0, 0, 0], [1, 1, 1]], seed: -3}}\n"),
      HasSubstr("s.yaml:2: obstacle 'a' motion seed must be a non-negative integer"));
  // MoveIt files: a value of the wrong kind, and a map where the format has a list.
  EXPECT_THAT(error("world: {collision_objects: []}\nallowed_collision_matrix:\n  entry_names: "
                    "[a, b]\n  entry_values:\n    - [false, true]\n    - [maybe, false]\n"),
              HasSubstr("s.yaml:6: allowed_collision_matrix entry must be true or false"));
  EXPECT_THAT(error("world:\n  collision_objects:\n    - id: box\n      primitives: {type: box}\n"
                    "      primitive_poses: {position: [0, 0, 0]}\n"),
              HasSubstr("s.yaml:4: collision object 'box' primitives must be a list"));
  EXPECT_THAT(messageOf<FileError>([&] { loadScene(path("absent.yaml")); }),
              HasSubstr("absent.yaml: cannot open"));
}

TEST_F(SceneFiles, EveryShippedSceneLoads) {
  std::size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dataDirectory() / "scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    const Scene scene = loadScene(entry.path());
    EXPECT_GT(scene.size(), 0u) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 5u);
}

// The samples of ../shared/data/motion-bench-sample.
const std::filesystem::path kSamples =
    std::filesystem::path(FASTRON_SHARED_DIR) / "data/motion-bench-sample";

TEST(MoveItScene, ReadsTheBenchmarkSamples) {
  const Scene scene = loadScene(kSamples / "scene0001.yaml");
  ASSERT_GE(scene.size(), 6u);
  const Obstacle& can = scene.obstacle("Can1");
  const auto& cylinder = std::get<Cylinder>(can.shape);
  EXPECT_EQ(cylinder.length, 0.12);  // MoveIt cylinders are [height, radius]
  EXPECT_EQ(cylinder.radius, 0.03);
  EXPECT_NEAR(can.pose.translation().x(), 0.308907161037877, 1e-12);
  const Eigen::Quaterniond q(can.pose.linear());
  EXPECT_NEAR(std::abs(q.z()), 0.4966790222940755, 1e-9);
  EXPECT_TRUE(scene.allowedCollisions.allowed("panda_hand", "panda_leftfinger"));
  EXPECT_FALSE(scene.allowedCollisions.allowed("panda_hand", "panda_link0"));
  for (int i = 1; i <= 10; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "scene%04d.yaml", i);
    EXPECT_GT(loadScene(kSamples / name).size(), 0u) << name;
  }
}

TEST(MoveItScene, ReadsTheRequestsForThePanda) {
  const Robot panda = loadRobot("panda");
  for (int i = 1; i <= 10; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "request%04d.yaml", i);
    const PlanRequest request = loadMoveItRequest(kSamples / name);
    EXPECT_EQ(request.group, "panda_arm");
    EXPECT_EQ(actuatedConfiguration(panda, request.start, "start").size(), 7u) << name;
    EXPECT_EQ(actuatedConfiguration(panda, request.goal, "goal").size(), 7u) << name;
  }
  const PlanRequest first = loadMoveItRequest(kSamples / "request0001.yaml");
  EXPECT_NEAR(actuatedConfiguration(panda, first.goal, "goal")[0], -1.451140183264752, 1e-15);
  EXPECT_NEAR(actuatedConfiguration(panda, first.start, "start")[3], -2.356, 1e-15);
  NamedPositions partial{{"panda_joint1"}, {0.0}};
  EXPECT_THROW(actuatedConfiguration(panda, partial, "start"), InvalidArgument);
}

// What moveit_writer.h writes reads back as the same scene and request: shapes, poses (a turned
// box, a tilted cylinder) and joint values bit for bit.
TEST(MoveItWriter, ScenesAndRequestsReadBackAsWritten) {
  Scene scene;
  scene.add({"lid", Box{Eigen::Vector3d(0.7, 0.7, 0.04)}, makePose({0.9, -0.1, 1.3}, {0, 0.6, 0.3}),
             std::nullopt});
  scene.add({"ball", Sphere{0.05}, makePose({0.2, 0.3, 0.4}), std::nullopt});
  scene.add({"can", Cylinder{0.03, 0.14}, makePose({0.8, 0, 0.53}, {0.2, 0, 0}), std::nullopt});
  const std::string yaml = moveItSceneYaml(scene, "panda");
  EXPECT_THAT(yaml, HasSubstr("dimensions: [0.7, 0.7, 0.04]"));  // the shortest exact text
  const Scene read = parseMoveItScene(yaml, "written.yaml");
  ASSERT_EQ(read.size(), 3u);
  for (const Obstacle& o : scene.obstacles()) {
    const Obstacle& r = read.obstacle(o.name);
    EXPECT_EQ(r.shape.index(), o.shape.index()) << o.name;
    EXPECT_TRUE(r.pose.isApprox(o.pose, 1e-14)) << o.name;
  }
  EXPECT_EQ(std::get<Box>(read.obstacle("lid").shape).size, Eigen::Vector3d(0.7, 0.7, 0.04));
  EXPECT_EQ(std::get<Cylinder>(read.obstacle("can").shape).length, 0.14);
  EXPECT_EQ(std::get<Cylinder>(read.obstacle("can").shape).radius, 0.03);

  const PlanRequest request{
      "arm", {{"j1", "j2"}, {0.1, -2.356194490192345}}, {{"j1", "j2"}, {1.0 / 3.0, 1e-300}}};
  const PlanRequest back = parseMoveItRequest(moveItRequestYaml(request), "written.yaml");
  EXPECT_EQ(back.group, "arm");
  EXPECT_EQ(back.start.names, request.start.names);
  EXPECT_EQ(back.start.positions, request.start.positions);
  EXPECT_EQ(back.goal.names, request.goal.names);
  EXPECT_EQ(back.goal.positions, request.goal.positions);
}

TEST(MoveItWriter, RefusesWhatItCannotWrite) {
  Scene capsule;
  capsule.add({"rod", Capsule{0.05, 0.3}, makePose({1, 0, 0}), std::nullopt});
  EXPECT_THAT(messageOf<InvalidArgument>([&] { moveItSceneYaml(capsule, "r"); }),
              HasSubstr("obstacle 'rod' is a capsule"));
  Scene moved;
  moved.robotBase = makePose({0, 0, 1});
  EXPECT_THAT(messageOf<InvalidArgument>([&] { moveItSceneYaml(moved, "r"); }),
              HasSubstr("robot base must be the identity"));
  EXPECT_THAT(messageOf<InvalidArgument>([&] {
                moveItRequestYaml({"arm", {{"j1", "j2"}, {0.0}}, {{"j1"}, {0.0}}});
              }),
              HasSubstr("start has 2 joint names but 1 positions"));
  EXPECT_THAT(messageOf<InvalidArgument>([&] {
                moveItRequestYaml({"arm", {{"j1"}, {0.0}}, {{"j1"}, {std::nan("")}}});
              }),
              HasSubstr("goal position of 'j1' is not finite"));
}

// Not only the samples: object poses, several primitives, inline meshes, and bad input.
TEST_F(SceneFiles, MoveItFeaturesBeyondTheSamples) {
  const Scene scene = parseScene(R"(
world:
  collision_objects:
    - id: shelf
      pose: {position: [1, 0, 0], orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]}
      primitives:
        - {type: box, dimensions: [0.5, 0.1, 0.02]}
        - {type: sphere, dimensions: [0.05]}
      primitive_poses:
        - {position: [0.1, 0, 0], orientation: [0, 0, 0, 1]}
        - {position: [0, 0, 0.3], orientation: [0, 0, 0, 1]}
    - id: wedge
      meshes:
        - vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
          triangles: [{vertex_indices: [0, 1, 2]}, {vertex_indices: [0, 1, 3]}]
      mesh_poses: [{position: [0, 0, 0], orientation: [0, 0, 0, 1]}]
)",
                                 "m.yaml");
  ASSERT_EQ(scene.size(), 3u);
  // The primitive pose is relative to the object pose (turned 90 degrees about z).
  EXPECT_LT((scene.obstacle("shelf/0").pose.translation() - Eigen::Vector3d(1, 0.1, 0)).norm(),
            1e-12);
  EXPECT_EQ(std::get<Mesh>(scene.obstacle("wedge").shape).mesh->triangles.size(), 2u);

  auto moveitError = [&](const std::string& yaml) {
    return messageOf<FileError>([&] { parseMoveItScene(yaml, "m.yaml"); });
  };
  EXPECT_THAT(moveitError("world:\n  collision_objects:\n    - id: c\n      primitives: [{type: "
                          "cone, dimensions: [1, 1]}]\n"
                          "      primitive_poses: [{position: [0, 0, 0]}]\n"),
              HasSubstr("m.yaml:4: collision object 'c': primitive type 'cone' is not supported"));
  EXPECT_THAT(moveitError("world:\n  collision_objects:\n    - id: c\n      primitives: [{type: "
                          "box, dimensions: [1, 1]}]\n"
                          "      primitive_poses: [{position: [0, 0, 0]}]\n"),
              HasSubstr("box dimensions must be a list of 3 numbers"));
  EXPECT_THAT(moveitError("world:\n  collision_objects:\n    - id: c\n      primitives: [{type: "
                          "box, dimensions: [1, 1, 1]}]\n"),
              HasSubstr("one primitive_pose per primitive"));
  EXPECT_THAT(moveitError("robot_state: {}\n"), HasSubstr("not a MoveIt PlanningScene"));
}

// Found by fuzz/scene_fuzzer: yaml-cpp's message for a bad escape quotes the escaped character,
// a control character included; the error names it as an escape.
TEST_F(SceneFiles, AMalformedEscapeIsReportedOnOneLine) {
  const std::string message = error("obstacles:\n  - {name: \"a\\\x01\"}\n");
  EXPECT_THAT(message, HasSubstr("s.yaml:2: malformed YAML: unknown escape character: \\x01"));
}

}  // namespace
}  // namespace fastron
