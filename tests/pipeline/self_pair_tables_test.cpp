// The robot's self-pair tables, built once and kept in a cache keyed by all they depend on.

#include "fastron/pipeline/self_pair_tables.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/robot_library.h"
#include "temp_dir.h"

namespace fastron::pipeline {
namespace {

using ::testing::HasSubstr;

class SelfPairTablesCache : public test::TempDir {
 protected:
  // Coarse tables: built in a fraction of a second.
  SelfPairTablesOptions options() const { return {.slack = 0.03, .cacheDirectory = path("cache")}; }
  static const Robot& panda() {
    static const Robot robot = loadRobot("panda-mesh");
    return robot;
  }
};

TEST_F(SelfPairTablesCache, BuiltOnceThenReadBackTheSame) {
  const SelfPairTables first = selfPairTables(panda(), options());
  EXPECT_FALSE(first.fromCache);
  EXPECT_GT(first.buildSeconds, 0);
  EXPECT_TRUE(first.warning.empty()) << first.warning;
  ASSERT_TRUE(first.tables);
  EXPECT_GE(first.tables->size(), 2U);
  EXPECT_EQ(first.file.parent_path(), path("cache"));
  EXPECT_THAT(first.file.filename().string(), ::testing::StartsWith("panda-"));
  EXPECT_TRUE(std::filesystem::is_regular_file(first.file));

  const SelfPairTables again = selfPairTables(panda(), options());
  EXPECT_TRUE(again.fromCache);
  EXPECT_EQ(again.buildSeconds, 0);
  ASSERT_EQ(again.tables->size(), first.tables->size());
  for (std::size_t i = 0; i < first.tables->size(); ++i)
    EXPECT_EQ((*again.tables)[i].distance, (*first.tables)[i].distance);
  // As a checker builds them.
  const FclChecker built(panda(), Scene{}, {.selfCollision = true, .selfPairSlack = 0.03});
  ASSERT_EQ(built.selfPairTables()->size(), first.tables->size());
  EXPECT_EQ(built.selfPairTables()->front().distance, first.tables->front().distance);
}

// A changed SRDF (an allowed pair), slack or padding is another file.
TEST_F(SelfPairTablesCache, WhatTheTablesDependOnChangesTheKey) {
  const std::uint64_t key = selfPairTablesKey(panda(), options());
  EXPECT_EQ(key, selfPairTablesKey(loadRobot("panda-mesh"), options()));
  Robot allowed = panda();
  allowed.allowedCollisions().allow("panda_link5", "panda_hand");
  EXPECT_NE(selfPairTablesKey(allowed, options()), key);
  SelfPairTablesOptions finer = options();
  finer.slack = 0.02;
  EXPECT_NE(selfPairTablesKey(panda(), finer), key);
  SelfPairTablesOptions padded = options();
  padded.padding = 0.01;
  EXPECT_NE(selfPairTablesFile(panda(), padded), selfPairTablesFile(panda(), options()));
}

TEST_F(SelfPairTablesCache, AFileThatCannotBeReadOrIsAnotherRobotsIsBuiltAgain) {
  const std::filesystem::path file = selfPairTablesFile(panda(), options());
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << "fastron self-pair tables 1\nkey 1\ntables 0\nend\n";  // another key
  EXPECT_FALSE(selfPairTables(panda(), options()).fromCache);
  EXPECT_TRUE(selfPairTables(panda(), options()).fromCache);
  std::ofstream(file) << "cut";
  EXPECT_FALSE(selfPairTables(panda(), options()).fromCache);
}

TEST_F(SelfPairTablesCache, RobotsWithoutSelfPairsOfMeshesNeedNone) {
  EXPECT_TRUE(hasMeshSelfPairs(panda()));
  const Robot ur3 = loadRobot("ur3");  // primitives
  EXPECT_FALSE(hasMeshSelfPairs(ur3));
  const SelfPairTables none = selfPairTables(ur3, options());
  EXPECT_FALSE(none.tables);
  EXPECT_TRUE(none.file.empty());
  EXPECT_FALSE(std::filesystem::exists(path("cache")));
}

// Tables that cannot be kept serve the run all the same, with a warning that says why.
TEST_F(SelfPairTablesCache, TablesThatCannotBeKeptStillServe) {
  std::ofstream(path("file")) << "x";
  SelfPairTablesOptions blocked = options();
  blocked.cacheDirectory = path("file") / "cache";
  const SelfPairTables tables = selfPairTables(panda(), blocked);
  ASSERT_TRUE(tables.tables);
  EXPECT_GE(tables.tables->size(), 2U);
  EXPECT_THAT(tables.warning, HasSubstr("self-pair tables not kept: "));
  EXPECT_THAT(tables.warning, HasSubstr("cannot make the cache folder"));
}

}  // namespace
}  // namespace fastron::pipeline
