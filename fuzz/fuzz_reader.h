#pragma once
// What every fuzz target checks about a reader, whatever the bytes: it returns a value, or it
// throws a fastron::Error whose message is one line that names the source. Any other exception,
// a crash, a leak, a sanitizer report or a hang is a finding (docs/reliability.md).

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "fastron/core/error.h"

namespace fastron::fuzz {

inline std::string textOf(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

[[noreturn]] inline void finding(const std::string& what, const std::string& message) {
  std::fprintf(stderr, "fuzz finding: %s\nmessage: [%s]\n", what.c_str(), message.c_str());
  std::abort();
}

/// Runs `read`; a fastron::Error must name `source` on one non-empty line.
template <class Read>
void readOrRefuse(const std::string& source, Read read) {
  try {
    read();
  } catch (const Error& e) {
    const std::string_view message = e.what();
    if (message.find(source) == std::string_view::npos)
      finding("the error does not name " + source, e.what());
    if (message.find('\n') != std::string_view::npos)
      finding("the error is not one line", e.what());
  }
}

}  // namespace fastron::fuzz
