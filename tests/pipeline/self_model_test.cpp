// The robot's self-collision model, learned once and kept in a cache keyed by all it depends on.

#include "fastron/pipeline/self_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <numbers>
#include <span>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/core/metrics.h"
#include "fastron/core/model.h"
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

  // It models the robot's self-collisions over the robot's whole range (through its checker,
  // which wraps the joints of two turns onto the one it learned): better than always answering
  // the commoner label.
  const FclChecker fcl(ur3, Scene{}, {.selfCollision = true});
  const Labels truth = labelConfigurations(fcl, q, 1);
  const auto checker = selfModelChecker(ur3, again.model);
  const Labels answers = labelConfigurations(*checker, q, 1);
  Configurations turned = q;  // the same poses, the shoulder pan a turn away
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    turned(i, 0) += q(i, 0) > 0 ? -6.283185307179586 : 6.283185307179586;
  EXPECT_EQ(labelConfigurations(*checker, turned, 1), answers);
  ConfusionCounts quality;
  for (std::size_t i = 0; i < truth.size(); ++i) quality.add(answers[i] > 0, truth[i] > 0);
  const double colliding =
      static_cast<double>(quality.truePositives + quality.falseNegatives) / 500.0;
  EXPECT_GT(quality.accuracy(), std::max(colliding, 1 - colliding));
}

// A UR3's joints of two turns (+-2 pi) are learned on one: the same pose repeats every turn. The
// elbow's single turn (+-pi) is left as it is.
TEST(SelfModelLimits, JointsOfMoreThanATurnAreLearnedOnOne) {
  const Robot ur3 = loadRobot("ur3");
  const JointLimits limits = selfModelLimits(ur3);
  const std::vector<std::string> names = ur3.actuatedJointNames();
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    SCOPED_TRACE(names[i]);
    EXPECT_GT(ur3.limits().upper()[k] - ur3.limits().lower()[k], 2 * std::numbers::pi - 1e-9);
    EXPECT_DOUBLE_EQ(limits.lower()[k], -std::numbers::pi);
    EXPECT_DOUBLE_EQ(limits.upper()[k], std::numbers::pi);
  }
  // A robot of narrower joints keeps its limits.
  const Robot panda = loadRobot("panda");
  EXPECT_EQ(selfModelLimits(panda).lower(), panda.limits().lower());
  EXPECT_EQ(selfModelLimits(panda).upper(), panda.limits().upper());
}

// A whole turn that takes `value`, within [-pi, pi], to the same angle within +-2 pi.
double aTurnWithin(double value) {
  return value > 0 ? -2 * std::numbers::pi : 2 * std::numbers::pi;
}

// The checker answers a configuration as the model answers the same pose on its one turn, so q
// and q + 2 pi on a joint of two turns get one answer; a model of the robot's own limits (a file
// of an earlier version) answers as it is.
TEST(SelfModelLimits, TheCheckerWrapsJointsOntoTheTurnTheModelLearned) {
  const Robot ur3 = loadRobot("ur3");
  Rng rng(9);
  const Configurations points = uniformConfigurations(selfModelLimits(ur3), 40, rng);
  const Eigen::VectorXd weights = Eigen::VectorXd::LinSpaced(40, -3, 3);
  const auto oneTurn =
      std::make_shared<const Model>(FeatureMap::jointScaling(selfModelLimits(ur3)),
                                    Kernel{KernelType::RationalQuadratic, 5}, points, weights);
  const auto checker = selfModelChecker(ur3, oneTurn);
  EXPECT_EQ(checker->name(), "Fastron self");
  EXPECT_TRUE(checker->answersFromAModel());
  const Configurations q = uniformConfigurations(selfModelLimits(ur3), 200, rng);
  std::size_t colliding = 0;
  const auto answerOf = [&](const Eigen::VectorXd& v) {
    return checker->inCollision(
        std::span<const double>(v.data(), static_cast<std::size_t>(v.size())));
  };
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const Eigen::VectorXd same = q.row(i).transpose();
    Eigen::VectorXd turned = same;
    turned[0] += aTurnWithin(turned[0]);  // shoulder pan, +-2 pi
    turned[4] += aTurnWithin(turned[4]);  // wrist 2, +-2 pi
    const bool answer = oneTurn->inCollision(same.data());
    EXPECT_EQ(answerOf(same), answer);
    EXPECT_EQ(answerOf(turned), answer);
    colliding += answer;
  }
  EXPECT_GT(colliding, 0u);  // both answers were asked
  EXPECT_LT(colliding, 200u);
  // A run of states (a planner's edge) is wrapped block by block: its free states first, each a
  // turn away, then its colliding ones; the first collision is found past the first blocks.
  Configurations edge(q.rows(), q.cols());
  Eigen::Index row = 0;
  for (const bool colliding : {false, true}) {
    for (Eigen::Index i = 0; i < q.rows(); ++i) {
      if (oneTurn->inCollision(q.row(i).data()) != colliding) continue;
      edge.row(row) = q.row(i);
      edge(row, 3) += aTurnWithin(edge(row, 3));  // wrist 1, +-2 pi
      ++row;
    }
  }
  const std::size_t free = 200 - colliding;
  ASSERT_GT(free, 32u);
  EXPECT_EQ(checker->firstInCollision(edge), free);

  const auto wholeRange =
      std::make_shared<const Model>(FeatureMap::jointScaling(ur3.limits()),
                                    Kernel{KernelType::RationalQuadratic, 5}, points, weights);
  const auto asItIs = selfModelChecker(ur3, wholeRange, "mine");
  EXPECT_EQ(asItIs->name(), "mine");
  Eigen::VectorXd far = Eigen::VectorXd::Constant(6, 0.5);
  far[0] = 5.0;
  EXPECT_EQ(asItIs->inCollision(std::span<const double>(far.data(), 6)),
            wholeRange->inCollision(far.data()));

  EXPECT_THROW(selfModelChecker(ur3, nullptr), InvalidArgument);
  EXPECT_THROW(selfModelChecker(loadRobot("panda"), oneTurn), InvalidArgument);
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
