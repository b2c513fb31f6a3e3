// RomDatabase.optimize: `mastrom optimize` from Python (rom/studies/optimization.hpp), the same
// rounds and numbers; bound in rom_bindings.cpp, which owns the RomDatabase class.
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

#include "rom/database/rom_database.hpp"

namespace mastrom::python {

/// See the docstring kOptimizeDoc.
pybind11::dict optimizeDatabase(const rom::RomDatabase& db,
                                const std::optional<std::string>& minimize,
                                const std::optional<std::string>& maximize,
                                const std::vector<std::string>& subject_to, pybind11::handle set,
                                pybind11::handle bounds, int rounds, int starts, int candidates,
                                const std::optional<std::string>& path);

extern const char* const kOptimizeDoc;

}  // namespace mastrom::python
