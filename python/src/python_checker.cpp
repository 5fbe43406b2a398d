#include "python_checker.h"

#include <pybind11/numpy.h>

#include <algorithm>

#include "fastron/core/error.h"

namespace fastron::python {

namespace py = pybind11;

PythonChecker::PythonChecker(py::function fn, std::size_t dof, std::string name)
    : fn_(std::move(fn)), dof_(dof), name_(std::move(name)) {
  if (dof == 0) throw InvalidArgument("a collision checker needs at least one joint (dof 0)");
}

PythonChecker::~PythonChecker() {
  // The last owner may be a C++ thread that does not hold the GIL.
  py::gil_scoped_acquire gil;
  fn_ = py::function();
}

bool PythonChecker::check(const double* q) const {
  py::gil_scoped_acquire gil;
  py::array_t<double> array(static_cast<py::ssize_t>(dof_));
  std::copy(q, q + dof_, array.mutable_data());
  return fn_(array).cast<bool>();
}

}  // namespace fastron::python
