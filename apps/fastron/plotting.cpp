#include "plotting.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>

#include "fastron/core/install_location.h"

extern char** environ;

namespace fastron::cli {

std::string runPlotScript(const std::string& script, const std::vector<std::string>& args) {
  // FASTRON_SCRIPTS_DIR in the environment overrides the installation's share/fastron/scripts.
  const char* dirOverride = std::getenv("FASTRON_SCRIPTS_DIR");
  std::filesystem::path dir;
  if (dirOverride != nullptr && dirOverride[0] != '\0') {
    dir = dirOverride;
  } else if (auto share = installedShareDirectory()) {
    dir = *share / "scripts";
  } else {
    return "plot scripts not found (no share/fastron above the program; set FASTRON_SCRIPTS_DIR)";
  }
  const std::filesystem::path path = dir / script;
  if (!std::filesystem::exists(path)) return "plot script not found: " + path.string();
  if (::access(FASTRON_PYTHON, X_OK) != 0) {
    return std::string(FASTRON_PYTHON) + " not found (install python3-matplotlib)";
  }
  std::vector<std::string> argv{FASTRON_PYTHON, path.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargv;
  for (auto& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);

  // stdout of the script goes to stderr: the command's own stdout stays a clean report.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  pid_t pid = 0;
  const int spawnError =
      posix_spawn(&pid, FASTRON_PYTHON, &actions, nullptr, cargv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawnError != 0) return "cannot start " + std::string(FASTRON_PYTHON);
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return "lost the plot process";
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return script + " failed";
  return {};
}

}  // namespace fastron::cli
