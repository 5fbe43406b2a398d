#pragma once
// The self-pair table file: a robot's tables of self-pair distances (self_pair_table.h), kept so
// that they are built once per robot (pipeline::selfPairTables).
//
// Text, one field per line, numbers exact (doubles and floats in C's hexadecimal notation, %a):
//   fastron self-pair tables 1
//   key KEY                              (16 hex digits: what the tables were built for)
//   tables N
//   then N times:
//     table SHAPE_A SHAPE_B AXES
//     axis COORDINATE FIRST_NODE SPACING LEVER NODES     (AXES lines)
//     one distance per node, the first axis fastest
//   end

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/self_pair_table.h"

namespace FASTRON_API fastron {

struct SelfPairTableFile {
  std::uint64_t key = 0;  ///< the writer's: pipeline::selfPairTablesKey
  std::vector<SelfPairTable> tables;
};

/// Writes `file` to `path` atomically (writeFileAtomically); throws FileError when it cannot.
void saveSelfPairTables(const SelfPairTableFile& file, const std::filesystem::path& path);

/// Reads a self-pair table file; throws FileError naming the file, the line and the field at
/// fault (missing, not such a file, another version, a malformed or non-finite number, cut short,
/// a table that does not hold together: checkSelfPairTable without a robot's sizes).
SelfPairTableFile loadSelfPairTables(const std::filesystem::path& path);

/// loadSelfPairTables on the text of a file; errors name `source`.
SelfPairTableFile parseSelfPairTables(std::string_view text, const std::string& source);

}  // namespace fastron
