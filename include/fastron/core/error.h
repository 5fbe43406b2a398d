#pragma once
// The exceptions the library throws. Library code never prints or exits: it throws one of these
// with a message that names the file, line, field or value at fault.

#include <stdexcept>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// Base of every exception thrown by Fastron.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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

}  // namespace fastron
