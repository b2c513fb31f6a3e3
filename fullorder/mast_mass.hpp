// The mass of a mast and of each of its items, from the items' data alone (docs/theory.md §1.7):
// a module weighs what it is configured to weigh, an interface what its shell's volume holds,
//
//     m_k = ρ π (r_o² − r_i²) L_k = ρ · 2π R_k h_k · L_k,   r_o,i = R_k ± h_k/2,          (1.12)
//
// (the two forms agree exactly: r_o² − r_i² = 2 R h). The full order's assembled mass matrix holds
// the modules' masses exactly and the shells' up to the ring's geometric discretisation (its
// element mass is integrated over the interpolated surface: 5e-4 light at 8 elements per ring,
// falling like N_circ⁻⁴; tests/fullorder/test_mast_mass.cpp). Costs nothing next to a deployment,
// so every design description (screen, rom eval, validate, Python) carries it.
#pragma once

#include <vector>

#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {

/// The mass of one cylindrical shell of mid-surface radius R, wall thickness h, length L and
/// density ρ [kg]: ρ π (r_o² − r_i²) L, (1.12).
double shellMassKg(double radius_m, double thickness_m, double length_m, double density_kg_m3);

/// The masses of a mast's items, numbered from the base (0-based here; module k + 1 and interface
/// k + 1 in the configuration's numbering).
struct MastMass {
  std::vector<double> module_kg;     ///< n modules
  std::vector<double> interface_kg;  ///< n − 1 interfaces
  double total_kg = 0.0;             ///< all of them
};

/// The masses of the mast `params` describes (modules as configured, shells from (1.12)).
MastMass mastMass(const MastParameters& params);

}  // namespace mastrom::fullorder
