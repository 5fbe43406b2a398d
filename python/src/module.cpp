// The fastron Python module (imported as fastron; this extension is fastron._fastron).

#include <ompl/util/Console.h>

#include "bindings.h"

PYBIND11_MODULE(_fastron, m) {
  m.doc() =
      "Fastron: learned proxy collision detection for robot motion planning (Das and Yip). "
      "Configurations are numpy arrays of joint values, shape (d,) for one and (n, d) for many; "
      "labels are +1 (in collision) and -1 (free).";
  // OMPL's console messages are the library's; a Python program gets results and exceptions.
  ompl::msg::noOutputHandler();
  fastron::python::bindErrors(m);
  fastron::python::bindCore(m);
  fastron::python::bindGeometry(m);
  fastron::python::bindSceneCheckers(m);
  fastron::python::bindProxy(m);
  fastron::python::bindPlanning(m);
  fastron::python::bindTrajectories(m);
  fastron::python::bindPipeline(m);
}
