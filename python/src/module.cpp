// Entry point of the compiled part of the Python package `mastrom` (python/mastrom/__init__.py
// re-exports it). Everything the module computes is done by the same library functions as the
// `mastrom` command line, so results agree with it bit for bit.
#include <pybind11/pybind11.h>

#include <string>

#include "common/option_names.hpp"
#include "common/version.hpp"
#include "python/src/bindings.hpp"

PYBIND11_MODULE(_core, m) {
  m.doc() =
      "mastrom: deployment dynamics and parameter-interpolated modal ROM of a modular rover mast "
      "(compiled core; use the package `mastrom`).";
  m.attr("__version__") = std::string(mastrom::kVersion);
  // Messages name the keyword arguments of the calls, not the command line's flags.
  mastrom::useFrontEnd(mastrom::FrontEnd::Python);
  mastrom::python::bindErrors(m);
  mastrom::python::bindConfig(m);
  mastrom::python::bindFullOrder(m);
  mastrom::python::bindRom(m);
}
