#include "fastron/core/install_location.h"

#include <dlfcn.h>

#include <system_error>

namespace fastron {

namespace {

/// The file of the executable or shared library this function was loaded from.
std::filesystem::path thisModule() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&thisModule), &info) != 0 && info.dli_fname != nullptr &&
      info.dli_fname[0] == '/') {
    return info.dli_fname;
  }
  return "/proc/self/exe";  // dladdr names the main program as it was started (maybe relative)
}

}  // namespace

std::optional<std::filesystem::path> installedShareDirectory() {
  std::error_code error;
  const std::filesystem::path module = std::filesystem::canonical(thisModule(), error);
  if (error) return std::nullopt;
  for (std::filesystem::path dir = module.parent_path();; dir = dir.parent_path()) {
    const std::filesystem::path share = dir / "share" / "fastron";
    if (std::filesystem::is_regular_file(share / "robots" / "robots.yaml", error)) return share;
    if (dir == dir.root_path() || dir.empty()) return std::nullopt;
  }
}

}  // namespace fastron
