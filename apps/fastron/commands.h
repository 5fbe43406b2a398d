#pragma once
// The subcommands of `fastron`. Each adds itself to the app; its callback stores the exit code.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>

namespace fastron {
enum class PathSimplification : std::uint8_t;  // fastron/planning/planner.h
}

namespace fastron::cli {

/// Accepts a number above `minimum` (or equal to it when `inclusive`). CLI11's PositiveNumber
/// prints the whole range of double in its message.
inline CLI::Validator numberAbove(double minimum, bool inclusive = false) {
  char bound[32];
  std::snprintf(bound, sizeof bound, "%g", minimum);
  const std::string what = std::string(inclusive ? "at least " : "above ") + bound;
  return CLI::Validator(
      [=](const std::string& text) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
        const bool ok = inclusive ? value >= minimum : value > minimum;
        return ok ? std::string() : "must be " + what + ", got " + text;
      },
      inclusive ? "NONNEGATIVE" : "POSITIVE");
}

/// --simplification full|shortcuts (any case), handed to `set`; `scope` begins the help, e.g.
/// "planning experiments: ". Defined in plan_command.cpp, so that this header, which every
/// command includes, does not bring OMPL's headers along.
void addSimplificationOption(CLI::App& cmd, std::function<void(PathSimplification)> set,
                             const std::string& scope = "");

void addTrainCommand(CLI::App& app, int& exitCode);
void addEvalCommand(CLI::App& app, int& exitCode);
void addDemoCommand(CLI::App& app, int& exitCode);
void addCheckCommand(CLI::App& app, int& exitCode);
void addRobotsCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);
void addPlanCommand(CLI::App& app, int& exitCode);
void addSampleCommand(CLI::App& app, int& exitCode);
void addProblemsCommand(CLI::App& app, int& exitCode);

}  // namespace fastron::cli
