#pragma once
// The parts of the fastron Python module, one per layer of the library.

#include <pybind11/pybind11.h>

namespace fastron::python {

void bindErrors(pybind11::module_& m);
void bindCore(pybind11::module_& m);
void bindGeometry(pybind11::module_& m);
/// SceneChecker, FclChecker, GjkChecker and the factory by name.
void bindSceneCheckers(pybind11::module_& m);
void bindProxy(pybind11::module_& m);
void bindPlanning(pybind11::module_& m);
void bindTrajectories(pybind11::module_& m);
void bindPipeline(pybind11::module_& m);

}  // namespace fastron::python
