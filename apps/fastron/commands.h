#pragma once
// The subcommands of `fastron`. Each adds itself to the app; its callback stores the exit code.

#include <CLI/CLI.hpp>

namespace fastron::cli {

void addTrainCommand(CLI::App& app, int& exitCode);
void addEvalCommand(CLI::App& app, int& exitCode);
void addDemoCommand(CLI::App& app, int& exitCode);
void addCheckCommand(CLI::App& app, int& exitCode);
void addRobotsCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);

}  // namespace fastron::cli
