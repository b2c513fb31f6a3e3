// RomDatabase.screen's designs between Python and the library: a mapping {key: values} becomes the
// design columns of rom/studies/design_screen.hpp (names for str values, numbers otherwise; one value
// broadcast to every design, as NumPy broadcasts a scalar), and the table comes back as a dict of
// (N,) arrays.
#pragma once

#include <pybind11/pybind11.h>

#include <vector>

#include "rom/studies/design_screen.hpp"

namespace mastrom::python {

/// The columns of `designs` (a mapping). TypeError for a value that is neither a number, a 1-D
/// array of numbers, a str nor a sequence of str. Lengths are checked by the screen itself.
std::vector<rom::DesignColumn> designColumns(pybind11::handle designs);

/// The design columns (float64, or str for names) followed by the metrics (float64; `settled` as
/// bool), each (N,).
pybind11::dict screenTableDict(const std::vector<rom::DesignColumn>& columns,
                               const rom::DesignScreenTable& table);

}  // namespace mastrom::python
