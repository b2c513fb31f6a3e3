// Python values → the `section.key=value` overrides of the command line's `--set`, so that every
// value a Python caller gives goes through the same parser and validation as on the command line.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace mastrom::python {

/// The TOML text of one value: bool → true/false, int → digits, float → shortest round-trip
/// decimal (the same double after parsing), str → a quoted TOML string, a sequence or 1-D array →
/// [a, b, …]. NumPy scalars count as their Python kind. TypeError for anything else.
std::string tomlValue(pybind11::handle value);

/// `set=` of the API: None, a mapping {"section.key": value}, or an iterable of "section.key=value"
/// strings (the command line's spelling). Mappings keep their order (overrides apply in order).
std::vector<std::string> overridesFrom(pybind11::handle set);

}  // namespace mastrom::python
