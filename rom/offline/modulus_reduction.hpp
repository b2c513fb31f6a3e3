// Young's modulus handled exactly instead of sampled (docs/theory.md §4.4 (e),
// rom/model/modulus_scaling.hpp): when E is one of a build's parameters and gravity is off, the
// modes at any E are those at a reference E₀ with ω and ζ scaled by √(E/E₀) and the modal stresses
// by E/E₀. The build then samples the other axes only, at E₀ (the box's geometric mean, the centre
// of the log-coordinate the interpolators use), and the database records the reduction
// (RomDatabase::exact_modulus); its error estimate runs in the sampled space. With gravity the
// preload's geometric stiffness and σ̄ depend on E otherwise, and E is sampled like any axis.
#pragma once

#include <string>
#include <vector>

#include "common/config.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

struct ModulusReduction {
  int axis = -1;              ///< the E axis among the build's axes; −1: E is sampled (or no axis)
  double reference_pa = 0.0;  ///< E₀ the samples are solved at
  std::string reason;         ///< one line on why E is or is not handled exactly; empty: no E axis
  bool applies() const { return axis >= 0; }
};

/// Whether a build of `base` over `axes` handles Young's modulus exactly: it does when E is an
/// axis, at least one other axis is sampled and gravity is off.
ModulusReduction planModulusReduction(const Config& base, const std::vector<ParameterAxis>& axes);

/// The base configuration of the reduced build: `base` at E₀.
Config reducedBuildBase(const Config& base, const ModulusReduction& plan);
/// The axes of the reduced build: `axes` without the E axis.
std::vector<ParameterAxis> reducedBuildAxes(const std::vector<ParameterAxis>& axes,
                                            const ModulusReduction& plan);
/// The database of the reduced build made the user's: the E axis back at its place with the box
/// {lo, hi} of `e_axis`, every sample's parameter on it E₀, the stored configuration's E that of
/// `base`, and the reduction recorded.
void restoreModulusAxis(RomDatabase& db, const Config& base, const ParameterAxis& e_axis,
                        const ModulusReduction& plan);

}  // namespace mastrom::rom
