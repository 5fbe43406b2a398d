#pragma once
// Plots are drawn by matplotlib scripts in scripts/, run with Debian's /usr/bin/python3.

#include <filesystem>
#include <string>
#include <vector>

namespace fastron::cli {

/// Runs scripts/<script> with `args`. Returns an empty string on success, otherwise why it failed
/// (missing interpreter or script, non-zero exit). The script's own output goes to stderr.
std::string runPlotScript(const std::string& script, const std::vector<std::string>& args);

}  // namespace fastron::cli
