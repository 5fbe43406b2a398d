// fastron.Error and its subclasses, each also derived from the matching builtin exception, so
// that `except ValueError` and `except FileNotFoundError` catch what they should.

#include <pybind11/pybind11.h>

#include "bindings.h"
#include "fastron/core/error.h"

namespace fastron::python {

namespace py = pybind11;

namespace {

/// A new exception class `name` of module m with these bases. Its reference is kept for the life
/// of the process (the translator below needs it; no destructor runs after the interpreter ends).
py::handle exceptionClass(py::module_& m, const char* name, const py::tuple& bases,
                          const char* doc) {
  py::dict attributes;
  attributes["__doc__"] = doc;
  attributes["__module__"] = "fastron";
  py::object cls = py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(&PyType_Type))(
      name, bases, attributes);
  m.attr(name) = cls;
  return cls.release();
}

}  // namespace

void bindErrors(py::module_& m) {
  const py::object builtins = py::module_::import("builtins");
  static py::handle error, invalid, file, notFound, oracle, unsupported;
  error = exceptionClass(m, "Error", py::make_tuple(builtins.attr("RuntimeError")),
                         "Base of every exception Fastron raises.");
  invalid = exceptionClass(m, "InvalidArgument", py::make_tuple(error, builtins.attr("ValueError")),
                           "A value cannot be used: wrong shape or dimension, NaN, out of range.");
  file = exceptionClass(m, "FileError", py::make_tuple(error, builtins.attr("OSError")),
                        "A file is unreadable or malformed; the message names the file and where.");
  notFound =
      exceptionClass(m, "FileNotFound", py::make_tuple(file, builtins.attr("FileNotFoundError")),
                     "A file that cannot be opened: it does not exist or is not readable.");
  oracle = exceptionClass(m, "OracleFault", py::make_tuple(error),
                          "The exact checker failed while labelling: it raised, passed its "
                          "deadline, or answered one configuration both ways.");
  unsupported = exceptionClass(
      m, "Unsupported", py::make_tuple(error, builtins.attr("NotImplementedError")),
      "The object cannot do what was asked (a scene checker that measures no distances).");
  py::register_exception_translator([](std::exception_ptr thrown) {
    // The most derived class first.
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const FileNotFound& e) {
      PyErr_SetString(notFound.ptr(), e.what());
    } catch (const FileError& e) {
      PyErr_SetString(file.ptr(), e.what());
    } catch (const InvalidArgument& e) {
      PyErr_SetString(invalid.ptr(), e.what());
    } catch (const Unsupported& e) {
      PyErr_SetString(unsupported.ptr(), e.what());
    } catch (const OracleFault& e) {
      PyErr_SetString(oracle.ptr(), e.what());
    } catch (const Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });
}

}  // namespace fastron::python
