#pragma once
// The exceptions the library throws. Library code never prints or exits: it throws one of these
// with a message that names the file, line, field or value at fault.

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

namespace detail {

/// `text` on one line: control characters that a quoted file excerpt or value can carry (a
/// newline inside an attribute, a tab, a NUL) are written as escapes (\n, \t, \x00).
inline std::string oneLine(std::string_view text) {
  std::string line;
  line.reserve(text.size());
  for (const char c : text) {
    if (c == '\n') {
      line += "\\n";
    } else if (c == '\r') {
      line += "\\r";
    } else if (c == '\t') {
      line += "\\t";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<unsigned char>(c));
      line += escaped;
    } else {
      line += c;
    }
  }
  return line;
}

}  // namespace detail

/// Base of every exception thrown by Fastron. Its message is always one line (detail::oneLine),
/// whatever text from a file it quotes.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(detail::oneLine(message)) {}
  explicit Error(const char* message) : Error(std::string(message)) {}
};

/// A value passed by the caller cannot be used: wrong dimension, NaN, out-of-range parameter.
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

/// A file is missing, unreadable or malformed; the message names the file and where it is wrong.
class FileError : public Error {
 public:
  using Error::Error;
};

/// A file that cannot be opened: it does not exist, or is not readable.
class FileNotFound : public FileError {
 public:
  using FileError::FileError;
};

/// An implementation cannot do what was asked (a scene checker that measures no distances); the
/// message names it and what was asked.
class Unsupported : public Error {
 public:
  using Error::Error;
};

/// The exact checker (the oracle) failed while labelling: it threw, passed its deadline, or gave
/// two answers for the same configuration. The message names the oracle and what it did.
class OracleFault : public Error {
 public:
  using Error::Error;
};

}  // namespace fastron
