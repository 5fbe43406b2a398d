// The self-pair table file: tables read back exactly as written, a checker given them answers as
// one that built them, and every malformed file is refused with its file, line and field.

#include "fastron/geometry/self_pair_table_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "fastron/core/active_learning.h"
#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_library.h"
#include "temp_dir.h"

namespace fastron {
namespace {

using ::testing::HasSubstr;

// Coarse tables (3 cm of slack): a few thousand nodes, built in a fraction of a second.
constexpr double kCoarse = 0.03;

class SelfPairTableFileTest : public test::TempDir {
 protected:
  static const Robot& panda() {
    static const Robot robot = loadRobot("panda-mesh");
    return robot;
  }
  static const std::vector<SelfPairTable>& tables() {
    static const std::vector<SelfPairTable> built =
        *FclChecker(panda(), Scene{}, {.selfCollision = true, .selfPairSlack = kCoarse})
             .selfPairTables();
    return built;
  }
  /// The file of a one-axis table of `nodes` distances, with `edit` applied to its text.
  std::filesystem::path small(const std::string& distances, std::size_t nodes = 2) const {
    return write("small.self-pairs",
                 "fastron self-pair tables 1\nkey 00000000000000ff\ntables 1\n"
                 "table 0 1 1\naxis 2 -0x1p+0 0x1p-2 0x1p-1 " +
                     std::to_string(nodes) + "\n" + distances + "end\n");
  }
};

TEST_F(SelfPairTableFileTest, TablesReadBackExactly) {
  ASSERT_GE(tables().size(), 2U);
  saveSelfPairTables({0x0123456789abcdefULL, tables()}, path("panda.self-pairs"));
  const SelfPairTableFile read = loadSelfPairTables(path("panda.self-pairs"));
  EXPECT_EQ(read.key, 0x0123456789abcdefULL);
  ASSERT_EQ(read.tables.size(), tables().size());
  for (std::size_t i = 0; i < tables().size(); ++i) {
    const SelfPairTable &a = tables()[i], &b = read.tables[i];
    EXPECT_EQ(b.shapeA, a.shapeA);
    EXPECT_EQ(b.shapeB, a.shapeB);
    EXPECT_EQ(b.axes, a.axes);
    EXPECT_EQ(b.coordinate, a.coordinate);
    EXPECT_EQ(b.lower, a.lower);
    EXPECT_EQ(b.spacing, a.spacing);
    EXPECT_EQ(b.lever, a.lever);
    EXPECT_EQ(b.nodes, a.nodes);
    EXPECT_EQ(b.distance, a.distance);  // bit for bit: hexadecimal floats
  }
  // An empty list is a file too (a robot whose mesh pairs no one or two coordinates turn).
  saveSelfPairTables({7, {}}, path("none.self-pairs"));
  EXPECT_TRUE(loadSelfPairTables(path("none.self-pairs")).tables.empty());
}

// A checker given the tables read back answers as the checker that built them, state by state.
TEST_F(SelfPairTableFileTest, ACheckerGivenTablesAnswersAsTheOneThatBuiltThem) {
  Scene scene;
  scene.add(Obstacle{"shelf", Box{{0.3, 0.6, 0.04}},
                     Eigen::Isometry3d(Eigen::Translation3d(0.6, 0, 0.5))});
  const FclChecker built(panda(), scene, {.selfCollision = true, .selfPairSlack = kCoarse});
  saveSelfPairTables({1, *built.selfPairTables()}, path("t.self-pairs"));
  const auto read = std::make_shared<const std::vector<SelfPairTable>>(
      loadSelfPairTables(path("t.self-pairs")).tables);
  const FclChecker given(panda(), scene, {.selfCollision = true, .selfPairTables = read});
  EXPECT_EQ(given.selfPairTableCount(), built.selfPairTableCount());
  EXPECT_EQ(given.selfPairTables(), read);  // shared, not copied
  const FclChecker dense(panda(), scene, {.selfCollision = true, .proveMotionsFree = false});
  Rng rng(5);
  const Configurations q = uniformConfigurations(panda().limits(), 400, rng);
  std::size_t colliding = 0;
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const Eigen::VectorXd row = q.row(i).transpose();
    const std::span<const double> at(row.data(), panda().dof());
    const bool expected = dense.inCollision(at);
    ASSERT_EQ(given.inCollision(at), expected) << "state " << i;
    ASSERT_EQ(built.inCollision(at), expected) << "state " << i;
    colliding += expected;
  }
  EXPECT_GT(colliding, 0U);
  // Tables are not read without self-collision or without clearance proofs: nothing to serve.
  EXPECT_EQ(FclChecker(panda(), scene, {.selfPairTables = read}).selfPairTableCount(), 0U);
}

TEST_F(SelfPairTableFileTest, ACheckerRefusesTablesThatDoNotFitItsRobot) {
  auto wrong = tables();
  wrong[0].shapeB = panda().shapes().size();
  const auto shared = std::make_shared<const std::vector<SelfPairTable>>(wrong);
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] {
                FclChecker(panda(), Scene{}, {.selfCollision = true, .selfPairTables = shared});
              }),
              HasSubstr("FclChecker of robot 'panda': self-pair table of shapes"));
  wrong = tables();
  wrong[0].coordinate[0] = panda().dof();
  const auto beyond = std::make_shared<const std::vector<SelfPairTable>>(wrong);
  EXPECT_THAT(test::messageOf<InvalidArgument>([&] {
                FclChecker(panda(), Scene{}, {.selfCollision = true, .selfPairTables = beyond});
              }),
              HasSubstr("coordinate 7 is not below 7"));
}

TEST_F(SelfPairTableFileTest, MalformedFilesAreRefusedWithTheirLine) {
  const auto refusal = [&](const std::filesystem::path& file) {
    return test::messageOf<FileError>([&] { loadSelfPairTables(file); });
  };
  EXPECT_NO_THROW(loadSelfPairTables(small("0x1p-4\n0x1p-3\n")));
  EXPECT_THAT(refusal(path("absent.self-pairs")), HasSubstr("absent.self-pairs"));
  EXPECT_THAT(refusal(write("model.fastron", "FASTRON\n")),
              HasSubstr("model.fastron:1: not a self-pair table file of version 1"));
  EXPECT_THAT(refusal(small("0x1p-4\n")), HasSubstr(":7: distance 'end' is not a finite number"));
  EXPECT_THAT(refusal(small("0x1p-4\nnan\n")),
              HasSubstr(":7: distance 'nan' is not a finite number"));
  EXPECT_THAT(refusal(small("0x1p-4\n0x1.000001p-3\n")),
              HasSubstr(":7: a distance is not a float"));
  EXPECT_THAT(refusal(small("", 0)), HasSubstr(":5: node count 0 is out of range"));
  EXPECT_THAT(refusal(small("0x1p-4\n0x1p-3\n0x1p-2\n")), HasSubstr(":8: expected 'end'"));
  EXPECT_THAT(refusal(write("cut.self-pairs", "fastron self-pair tables 1\nkey 1\ntables 2\n")),
              HasSubstr("cut.self-pairs:4: the file ends where table should be"));
  EXPECT_THAT(refusal(write("key.self-pairs", "fastron self-pair tables 1\nkey xyz\n")),
              HasSubstr("key.self-pairs:2: key 'xyz' is not a whole number"));
  EXPECT_THAT(refusal(write("axes.self-pairs",
                            "fastron self-pair tables 1\nkey 1\ntables 1\ntable 0 1 3\n")),
              HasSubstr("axes.self-pairs:4: axes must be 1 or 2"));
  EXPECT_THAT(refusal(write("same.self-pairs",
                            "fastron self-pair tables 1\nkey 1\ntables 1\n"
                            "table 3 3 1\naxis 0 0 0x1p-2 1 1\n0\nend\n")),
              HasSubstr("self-pair table of shapes 3 and 3: needs two distinct shapes"));
  EXPECT_THAT(refusal(write("spacing.self-pairs",
                            "fastron self-pair tables 1\nkey 1\ntables 1\n"
                            "table 0 1 1\naxis 0 0 -1 1 1\n0\nend\n")),
              HasSubstr("spacing must be finite and > 0"));
  EXPECT_THAT(refusal(write("words.self-pairs", "fastron self-pair tables 1\nkey 1 2\n")),
              HasSubstr("words.self-pairs:2: expected 'key' and 1 values, found 'key 1 2'"));
}

}  // namespace
}  // namespace fastron
