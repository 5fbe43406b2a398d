// fastron: learned proxy collision detection from the command line.

#include <malloc.h>
#include <CLI/CLI.hpp>

#include <ompl/util/Console.h>
#include <algorithm>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands.h"
#include "fastron/core/error.h"
#include "fastron/core/simd.h"

namespace {

// An error is one line, even when it quotes a file's text that holds line breaks.
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  // A model update allocates and frees about a megabyte (the new points, their features, the
  // trainer's grown matrices). With the command's evaluations between updates, glibc gave freed
  // memory at the top of its heap back to the system and the next update page-faulted it in again:
  // up to half a millisecond of a 7-joint update on the project's machine (docs/performance.md,
  // "Memory an update gives back"; updates alone, back to back, fault nothing). The command keeps
  // it; a program using the library can do the same (or set GLIBC_TUNABLES).
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
  CLI::App app{"Fastron: learned proxy collision detection for motion planning", "fastron"};
  app.set_version_flag("--version", FASTRON_VERSION);
  app.require_subcommand(1);
  // Applied while the command line is read, before the command runs (simd.h).
  app.add_option_function<std::string>(
         "--simd",
         [](const std::string& name) { fastron::useSimdPath(fastron::parseSimdPath(name)); },
         "SIMD instructions of the model's kernel sums: portable, avx2 or avx512 (default: the "
         "widest this processor runs, or $FASTRON_SIMD)")
      ->trigger_on_parse();
  // OMPL logs every planner's start and end on the console; the results carry what matters (a
  // plan's status), so the command keeps its output to its own tables.
  ompl::msg::noOutputHandler();
  int exitCode = 0;
  fastron::cli::addTrainCommand(app, exitCode);
  fastron::cli::addEvalCommand(app, exitCode);
  fastron::cli::addSampleCommand(app, exitCode);
  fastron::cli::addProblemsCommand(app, exitCode);
  fastron::cli::addDemoCommand(app, exitCode);
  fastron::cli::addCheckCommand(app, exitCode);
  fastron::cli::addRobotsCommand(app, exitCode);
  fastron::cli::addPlanCommand(app, exitCode);
  fastron::cli::addBenchCommand(app, exitCode);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // CLI11 checks required options before it complains about arguments it did not expect, so
    // `fastron trian` or `fastron train --dta x` would be told about a missing option; the
    // argument the user got wrong is the better message.
    const std::vector<std::string> unexpected = app.remaining(true);
    if (!unexpected.empty() && dynamic_cast<const CLI::RequiredError*>(&e) != nullptr) {
      const bool command = app.get_subcommands().empty();
      std::cerr << "fastron: error: unknown " << (command ? "command" : "argument") << " '"
                << unexpected.front() << "' (see fastron --help)\n";
      return 2;
    }
    std::cerr << "fastron: error: " << e.what() << " (see fastron --help)\n";
    return 2;
  } catch (const fastron::Error& e) {
    std::cerr << "fastron: error: " << oneLine(e.what()) << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fastron: internal error: " << oneLine(e.what()) << '\n';
    return 3;
  } catch (...) {
    std::cerr << "fastron: internal error: an exception of unknown type\n";
    return 3;
  }
  return exitCode;
}
