#include "fastron/pipeline/self_pair_tables.h"

#include <chrono>
#include <cstdio>
#include <variant>

#include "cache_key.h"
#include "fastron/core/error.h"
#include "fastron/geometry/fcl_checker.h"
#include "fastron/geometry/self_pair_table_file.h"
#include "fastron/pipeline/self_model.h"

namespace fastron::pipeline {
namespace {

/// Changes when the tables of the same robot and options would differ: their construction or
/// FclChecker's node limit.
constexpr std::uint32_t kTablesVersion = 1;

/// The cached tables, or null when the file is absent or not this robot's (another key, cut
/// short, or tables that do not fit it).
std::shared_ptr<const std::vector<SelfPairTable>> readCached(const std::filesystem::path& file,
                                                             const Robot& robot,
                                                             std::uint64_t key) {
  if (!std::filesystem::is_regular_file(file)) return nullptr;
  try {
    SelfPairTableFile read = loadSelfPairTables(file);
    if (read.key != key) return nullptr;
    for (const SelfPairTable& table : read.tables)
      checkSelfPairTable(table, robot.shapes().size(), robot.dof(), file.string());
    return std::make_shared<const std::vector<SelfPairTable>>(std::move(read.tables));
  } catch (const Error&) {
    return nullptr;
  }
}

}  // namespace

std::uint64_t selfPairTablesKey(const Robot& robot, const SelfPairTablesOptions& options) {
  Hash h;
  hashRobotCollisions(h, robot);
  h.value(options.slack);
  h.value(options.padding);
  h.value(kTablesVersion);
  return h.digest();
}

std::filesystem::path selfPairTablesFile(const Robot& robot, const SelfPairTablesOptions& options) {
  return cacheFile(options.cacheDirectory, robot, selfPairTablesKey(robot, options), "self-pairs");
}

bool hasMeshSelfPairs(const Robot& robot) {
  const auto mesh = [&](std::size_t s) {
    return std::holds_alternative<Mesh>(robot.shapes()[s].shape);
  };
  for (const auto& [a, b] : robot.selfCollisionPairs({})) {
    if (mesh(a) || mesh(b)) return true;
  }
  return false;
}

SelfPairTables selfPairTables(const Robot& robot, const SelfPairTablesOptions& options) {
  SelfPairTables result;
  if (!hasMeshSelfPairs(robot)) return result;
  const std::uint64_t key = selfPairTablesKey(robot, options);
  try {
    result.file = selfPairTablesFile(robot, options);
  } catch (const FileError& e) {  // no cache folder: built for this run alone
    result.warning = std::string("self-pair tables not kept: ") + e.what();
  }
  if (!result.file.empty() && (result.tables = readCached(result.file, robot, key))) {
    result.fromCache = true;
    return result;
  }
  const auto start = std::chrono::steady_clock::now();
  const FclChecker builder(robot, Scene{},
                           {.selfCollision = true,
                            .padding = options.padding,
                            .proveMotionsFree = true,
                            .selfPairSlack = options.slack});
  result.tables = builder.selfPairTables();
  result.buildSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (result.file.empty()) return result;
  try {
    std::error_code error;
    std::filesystem::create_directories(result.file.parent_path(), error);
    if (error) {
      throw FileError(result.file.parent_path().string() +
                      ": cannot make the cache folder: " + error.message());
    }
    saveSelfPairTables({key, *result.tables}, result.file);
  } catch (const FileError& e) {
    result.warning = std::string("self-pair tables not kept: ") + e.what();
  }
  return result;
}

}  // namespace fastron::pipeline
