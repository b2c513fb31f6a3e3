// The modal solve every part of the ROM starts from: the mast of a configuration locked at
// modes.angle_deg, its static equilibrium under the configured gravity and linearisation
// (modes/linearize.hpp), and its lowest constrained modes (modes/eigen_solver.hpp) — for a database
// sample, a direct modal model at one point and the first-frequency check of `validate`.
#pragma once

#include <string>

#include "common/config.hpp"
#include "common/kinds.hpp"
#include "fullorder/mast_model.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"

namespace mastrom::rom {

struct LockedModalSolve {
  fullorder::MastModel model;  ///< the locked mast
  modes::Linearization lin;
  modes::EigenResult eigen;  ///< the solved pairs, ω² ascending (canonical signs)
  double assembly_s = 0.0;   ///< mast model, equilibrium and linearisation [s]
  double eigensolve_s = 0.0;  ///< the eigen-solver backend alone [s]
};

/// Solve `config`'s locked mast for `wanted` + `margin` modes (the margin capped at the model's
/// free degrees of freedom; it lets a caller complete a degenerate cluster cut by `wanted`), on
/// MPI_COMM_SELF. Every error message starts with `where`: InputError when `wanted` exceeds the
/// free degrees of freedom, NumericalError when the equilibrium or the modal solve fails.
LockedModalSolve solveLockedMast(const Config& config, int wanted, int margin,
                                 EigenBackendKind backend, const std::string& where);

}  // namespace mastrom::rom
