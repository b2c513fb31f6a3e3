// The parts of the Python module `mastrom._core`, one function per file, called in this order by
// module.cpp. Each file binds one job: errors, the configuration, the full order (simulate, modes),
// the ROM database (evaluate, screen, build).
#pragma once

#include <pybind11/pybind11.h>

namespace mastrom::python {

void bindErrors(pybind11::module_& m);     ///< errors.cpp
void bindConfig(pybind11::module_& m);     ///< config_bindings.cpp
void bindFullOrder(pybind11::module_& m);  ///< full_order_bindings.cpp
void bindRom(pybind11::module_& m);        ///< rom_bindings.cpp

}  // namespace mastrom::python
