// Python exceptions for the library's errors. Every message is the library's one line, what
// `mastrom` prints after "mastrom: error: ", except that an option is named as the Python call's
// keyword argument (extrapolate=True where the command line says --extrapolate:
// common/option_names.hpp, chosen in module.cpp). The classes derive from the built-in exception a
// Python user expects, so `except ValueError` catches a bad configuration value without importing
// mastrom's own classes:
//   mastrom.Error            (Exception)            any failure the library reports on purpose
//   mastrom.InputError       (Error, ValueError)    a bad configuration value, key or argument
//   mastrom.FileError        (Error, OSError)       a file that cannot be read, written or is
//   corrupt mastrom.NumericalError   (Error, RuntimeError)  a diverging step, a failed eigen-solve,
//   …
#include <Python.h>

#include <exception>
#include <string>

#include "common/error.hpp"
#include "python/src/bindings.hpp"

namespace py = pybind11;

namespace mastrom::python {
namespace {

// Created once at import and kept for the life of the interpreter (module attributes hold them).
PyObject* error_type = nullptr;
PyObject* input_error_type = nullptr;
PyObject* file_error_type = nullptr;
PyObject* numerical_error_type = nullptr;

PyObject* newException(py::module_& m, const char* name, const char* doc, py::tuple bases) {
  const std::string qualified = std::string("mastrom.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));  // the module holds the reference
  return type;
}

}  // namespace

void bindErrors(py::module_& m) {
  error_type = newException(m, "Error", "Base of every error mastrom reports on purpose.",
                            py::make_tuple(py::handle(PyExc_Exception)));
  input_error_type = newException(
      m, "InputError",
      "Bad input: an unknown key, a wrong type, a value out of range, a point outside the "
      "database's box. The message names the key, the value and the allowed range.",
      py::make_tuple(py::handle(error_type), py::handle(PyExc_ValueError)));
  file_error_type = newException(
      m, "FileError", "A file that cannot be read or written, or that is not what it claims.",
      py::make_tuple(py::handle(error_type), py::handle(PyExc_OSError)));
  numerical_error_type = newException(
      m, "NumericalError",
      "A numerical method failed: a time step that does not converge, an eigen-solver that does "
      "not deliver the requested pairs. The message carries the time and the residuals.",
      py::make_tuple(py::handle(error_type), py::handle(PyExc_RuntimeError)));

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input_error_type, e.what());
    } catch (const IoError& e) {
      PyErr_SetString(file_error_type, e.what());
    } catch (const NumericalError& e) {
      PyErr_SetString(numerical_error_type, e.what());
    } catch (const Error& e) {
      PyErr_SetString(error_type, e.what());
    }
  });
}

}  // namespace mastrom::python
