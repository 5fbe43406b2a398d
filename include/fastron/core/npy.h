#pragma once
// NumPy's .npy format for 2-D arrays: read in place from a file's bytes, and written as float64.

#include <cstddef>
#include <string>
#include <string_view>

#include "fastron/core/export.h"

namespace FASTRON_API fastron {

/// A 2-D array in the bytes of a .npy file (format versions 1-3; dtypes <f8, <f4, <i8, <i4; C or
/// Fortran order), read in place: the bytes must outlive it.
class NpyMatrix {
 public:
  /// Throws FileError naming `source` for bad magic bytes, an unsupported version or dtype, a
  /// header without descr / fortran_order / shape, a shape that is not 2-D, or data shorter than
  /// the shape says (checked before anything is allocated).
  NpyMatrix(std::string_view bytes, const std::string& source);

  std::size_t rows() const { return rows_; }
  std::size_t columns() const { return columns_; }
  /// Element (r, c) as a double; r < rows(), c < columns().
  double at(std::size_t r, std::size_t c) const;

 private:
  std::string_view data_;  // the elements
  char type_ = 'f';        // 'f' or 'i'
  std::size_t itemSize_ = 8;
  bool fortran_ = false;
  std::size_t rows_ = 0, columns_ = 0;
};

/// The bytes of a .npy file (version 1.0) holding a float64 C-order array of shape
/// (rows, columns) whose elements are `values` row after row.
std::string npyBytes(const double* values, std::size_t rows, std::size_t columns);

}  // namespace fastron
