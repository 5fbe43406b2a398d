#pragma once
// Where Fastron's shared files (robots, scenes, plot scripts) are, found at run time: never a
// path compiled in, so that an installed library, a relocated prefix and the build tree all work.

#include <filesystem>
#include <optional>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// The folder `share/fastron` of the installation holding this code: looked for in the folder of
/// the binary or shared library that contains Fastron (an executable, libfastron_core.so, the
/// Python module) and in each folder above it. An install prefix has it as
/// `<prefix>/share/fastron`; the build tree makes one too (links to the source tree's data/ and
/// scripts/). Nothing when no such folder holds a robot catalogue (robots/robots.yaml).
std::optional<std::filesystem::path> installedShareDirectory();

}  // namespace fastron
