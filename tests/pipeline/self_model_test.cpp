// The robot's self-collision model, learned once and kept in a cache keyed by all it depends on.

#include "fastron/pipeline/self_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_library.h"
#include "fastron/proxy/labelling.h"
#include "temp_dir.h"

namespace fastron::pipeline {
namespace {

using ::testing::HasSubstr;

class SelfModelCache : public test::TempDir {
 protected:
  SelfModelOptions options() const {
    return {.samples = 3000, .updates = 1, .seed = 2, .cacheDirectory = path("cache")};
  }
};

TEST_F(SelfModelCache, TrainedOnceThenReadBackTheSame) {
  const Robot ur3 = loadRobot("ur3");
  const SelfModel first = selfCollisionModel(ur3, options());
  EXPECT_FALSE(first.fromCache);
  EXPECT_GT(first.trainSeconds, 0);
  EXPECT_TRUE(std::filesystem::is_regular_file(first.file));
  EXPECT_EQ(first.file.parent_path(), path("cache"));
  EXPECT_THAT(first.file.filename().string(), ::testing::StartsWith("ur3-"));

  const SelfModel again = selfCollisionModel(ur3, options());
  EXPECT_TRUE(again.fromCache);
  EXPECT_EQ(again.trainSeconds, 0);
  EXPECT_EQ(again.file, first.file);
  Rng rng(4);
  const Configurations q = uniformConfigurations(ur3.limits(), 500, rng);
  EXPECT_EQ(again.model->scoreBatch(q), first.model->scoreBatch(q));

  // It models the robot's self-collisions: better than always answering the commoner label.
  const FclChecker fcl(ur3, Scene{}, {.selfCollision = true});
  const Labels truth = labelConfigurations(fcl, q, 1);
  const ConfusionCounts quality = evaluate(*again.model, q, truth);
  const double colliding =
      static_cast<double>(quality.truePositives + quality.falseNegatives) / 500.0;
  EXPECT_GT(quality.accuracy(), std::max(colliding, 1 - colliding));
}

// A changed URDF (a shape), SRDF (an allowed pair), joint choice or training setting is another
// model; the cache never hands back one trained for something else.
TEST_F(SelfModelCache, WhatTheLabelsDependOnChangesTheKey) {
  const Robot ur3 = loadRobot("ur3");
  const std::uint64_t key = selfModelKey(ur3, options());
  EXPECT_EQ(key, selfModelKey(loadRobot("ur3"), options()));

  Robot allowed = ur3;
  allowed.allowedCollisions().allow("base_link", "forearm_link");
  EXPECT_NE(selfModelKey(allowed, options()), key);

  std::vector<LinkShape> shapes = ur3.shapes();
  shapes.back().shape = Sphere{0.123};
  EXPECT_NE(selfModelKey(Robot(ur3.name(), ur3.links(), ur3.joints(), shapes), options()), key);

  Robot fewer = ur3;
  fewer.setActuatedJoints({"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint"});
  EXPECT_NE(selfModelKey(fewer, options()), key);

  SelfModelOptions padded = options();
  padded.padding = 0.01;
  EXPECT_NE(selfModelKey(ur3, padded), key);
  SelfModelOptions more = options();
  more.samples = 4000;
  EXPECT_NE(selfModelFile(ur3, more), selfModelFile(ur3, options()));
}

TEST_F(SelfModelCache, AFileThatCannotBeReadIsTrainedAgain) {
  const Robot ur3 = loadRobot("ur3");
  const std::filesystem::path file = selfModelFile(ur3, options());
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << "not a model";
  const SelfModel model = selfCollisionModel(ur3, options());
  EXPECT_FALSE(model.fromCache);
  EXPECT_TRUE(selfCollisionModel(ur3, options()).fromCache);
}

TEST_F(SelfModelCache, TheCacheFolderComesFromTheEnvironment) {
  ::setenv("FASTRON_CACHE_DIR", path("mine").c_str(), 1);
  EXPECT_EQ(defaultCacheDirectory(), path("mine"));
  ::unsetenv("FASTRON_CACHE_DIR");
  ::setenv("XDG_CACHE_HOME", path("xdg").c_str(), 1);
  EXPECT_EQ(defaultCacheDirectory(), path("xdg") / "fastron");
  ::unsetenv("XDG_CACHE_HOME");
  // A cache folder that cannot be made is the caller's error, named.
  std::ofstream(path("file")) << "x";
  SelfModelOptions blocked = options();
  blocked.cacheDirectory = path("file") / "cache";
  EXPECT_THAT(test::messageOf<FileError>([&] { selfCollisionModel(loadRobot("rod2"), blocked); }),
              HasSubstr("cannot make the cache folder"));
}

}  // namespace
}  // namespace fastron::pipeline
