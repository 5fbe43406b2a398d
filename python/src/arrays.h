#pragma once
// numpy in and out: every array argument is checked here (shape, dtype, finite values) so that a
// mistake raises fastron.InvalidArgument naming the argument, its shape and the offending entry.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

#include "fastron/core/types.h"

namespace fastron::python {

namespace py = pybind11;

/// Configurations given as one (d,) array or a batch (n, d): a float64 C-ordered view of the
/// caller's array (copied only when its dtype or layout differs).
struct ConfigurationRows {
  py::array_t<double, py::array::c_style> array;  ///< keeps the data alive
  const double* data = nullptr;
  std::size_t rows = 0, cols = 0;
  bool single = false;  ///< given as one (d,) array
  /// The rows as a read-only Eigen matrix, without a copy.
  Eigen::Map<const Configurations> matrix() const {
    return {data, static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols)};
  }
  std::span<const double> row(std::size_t i) const { return {data + i * cols, cols}; }
};

/// `value` as configurations of `dim` joint values (dim 0: any). Throws InvalidArgument for an
/// object that is not numeric, a wrong number of dimensions or columns, and a NaN or infinite
/// entry (named by its index).
ConfigurationRows configurations(py::handle value, std::size_t dim, const char* name,
                                 bool allowSingle = true);
/// One configuration of `dim` values as an Eigen vector.
Eigen::VectorXd vector(py::handle value, std::size_t dim, const char* name);
/// Collision labels: booleans (True = collision) or numbers +1 / -1, one per row.
Labels labels(py::handle value, std::size_t rows, const char* name);

/// A new float64 array of shape (rows, cols) (cols 0: shape (rows,)) filled by the caller.
py::array_t<double> newArray(std::size_t rows, std::size_t cols = 0);
/// A read-only array over memory `owner` keeps alive (no copy).
py::array readOnlyView(const double* data, std::size_t rows, std::size_t cols, bool rowMajor,
                       py::handle owner);
/// A copy of an Eigen matrix or vector as an array; a vector gives shape (n,).
py::array_t<double> toArray(const Eigen::MatrixXd& m);
py::array_t<double> toArray(const Eigen::VectorXd& v);
py::array_t<double> toArray(const std::vector<double>& v);
/// Labels as an int8 array of +1 / -1.
py::array_t<std::int8_t> toArray(const Labels& labels);

}  // namespace fastron::python
