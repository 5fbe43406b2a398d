#pragma once
// Progress reports of long runs: the command prints them, the library never does.

#include <functional>
#include <string_view>

namespace fastron::experiments {

/// Called with a line of progress; the command prints it, the library never does.
using Progress = std::function<void(std::string_view)>;

}  // namespace fastron::experiments
