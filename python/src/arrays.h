#pragma once
// numpy in and out: every array argument is checked here (shape, dtype, finite values) so that a
// mistake raises fastron.InvalidArgument naming the argument, its shape and the offending entry.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <chrono>
#include <cstddef>
#include <span>
#include <string>
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

/// A copy of an Eigen matrix or vector (any storage order, any expression) as a C-ordered
/// array; a column vector gives shape (n,).
template <class Derived>
py::array_t<double> toArray(const Eigen::MatrixBase<Derived>& m) {
  const auto rows = static_cast<std::size_t>(m.rows()), cols = static_cast<std::size_t>(m.cols());
  constexpr bool vector = Derived::ColsAtCompileTime == 1;
  py::array_t<double> out = newArray(rows, vector ? 0 : cols);
  Eigen::Map<Configurations>(out.mutable_data(), m.rows(), m.cols()) = m;
  return out;
}
py::array_t<double> toArray(const std::vector<double>& v);
/// Labels as an int8 array of +1 / -1.
py::array_t<std::int8_t> toArray(const Labels& labels);

/// A read-only array over an Eigen matrix or vector that `owner` keeps alive (no copy); a column
/// vector gives shape (n,).
template <class Derived>
py::array readOnlyView(const Eigen::PlainObjectBase<Derived>& m, py::handle owner) {
  constexpr auto size = static_cast<py::ssize_t>(sizeof(double));
  std::vector<py::ssize_t> shape{m.rows()}, strides{Derived::IsRowMajor ? m.cols() * size : size};
  if constexpr (Derived::ColsAtCompileTime != 1) {
    shape.push_back(m.cols());
    strides.push_back(Derived::IsRowMajor ? size : m.rows() * size);
  }
  py::array view(py::dtype::of<double>(), shape, strides, m.data(), owner);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

/// A path of waypoints (planning/motion.h's JointPath) as a (k, d) array.
py::array_t<double> pathArray(const std::vector<Eigen::VectorXd>& path, std::size_t dim);
/// Waypoints (k, d) as a path of `dim` joint values each (dim 0: any); errors as configurations'.
std::vector<Eigen::VectorXd> pathOf(py::handle waypoints, std::size_t dim,
                                    const char* name = "path");

/// The Python type name of `value`, for messages.
std::string typeName(py::handle value);

}  // namespace fastron::python
