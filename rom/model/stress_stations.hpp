// The von Mises stress of a recovery point's three ζ stations from its six stress rows
// [σ_m; σ_b] (docs/theory.md (6.5)–(6.6); the row layout of rom/model/modal_stress.hpp): the one
// formula every stress evaluation of the ROM applies. Not part of the library's interface.
#pragma once

#include "fullorder/shell_stress.hpp"

namespace mastrom::rom::stress_detail {

/// Squared plane-stress von Mises of [a, b, c] (tensor shear c; fullorder/shell_stress.hpp).
inline double vonMises2(double a, double b, double c) {
  return a * a - a * b + b * b + 3.0 * c * c;
}

/// The squared von Mises of the stations ζ = −h/2, 0, +h/2 of a point from its rows
/// y = [σ_m; σ_b] (any indexable of six doubles).
template <class Rows>
void stationsOf(const Rows& y, double vm2[fullorder::kShellSurfaces]) {
  vm2[0] = vonMises2(y[0] - y[3], y[1] - y[4], y[2] - y[5]);
  vm2[1] = vonMises2(y[0], y[1], y[2]);
  vm2[2] = vonMises2(y[0] + y[3], y[1] + y[4], y[2] + y[5]);
}

}  // namespace mastrom::rom::stress_detail
