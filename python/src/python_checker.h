#pragma once
// An exact collision checker written in Python: any callable q -> bool.

#include <pybind11/pybind11.h>

#include <string>

#include "fastron/core/collision_checker.h"

namespace fastron::python {

/// Calls the Python callable with the configuration as a (d,) float64 array. Safe from any
/// thread: each call takes the GIL, so calls run one at a time (callers that label with a Python
/// oracle use one thread). An exception raised by the callable propagates to the caller.
class PythonChecker final : public CollisionChecker {
 public:
  PythonChecker(pybind11::function fn, std::size_t dof, std::string name);
  ~PythonChecker() override;
  std::string name() const override { return name_; }
  std::size_t dof() const override { return dof_; }

 protected:
  bool check(const double* q) const override;

 private:
  pybind11::function fn_;
  std::size_t dof_;
  std::string name_;
};

}  // namespace fastron::python
