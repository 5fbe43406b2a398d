#pragma once
// Whole files in and out: every reader of the library reads through readFile, and every writer
// replaces its file atomically, so that a crash while saving leaves the old file or the new one,
// never half of one.

#include <filesystem>
#include <string>
#include <string_view>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// The bytes of `path`; throws FileNotFound "<path>: cannot open <what>" when it cannot be opened
/// (missing, unreadable, or a folder).
std::string readFile(const std::filesystem::path& path, std::string_view what);

/// Writes `bytes` to a temporary file beside `path`, flushes it to disk, then renames it over
/// `path` (atomic on POSIX file systems). Throws FileError "<path>: cannot write <what>" and
/// leaves `path` as it was when any step fails.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes,
                         std::string_view what);

}  // namespace fastron
