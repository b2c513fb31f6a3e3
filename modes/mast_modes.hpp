// The modes of a run configuration, start to finish: the mast locked at modes.angle_deg, its static
// equilibrium and linearisation, the constrained eigenproblem with the configured backend and
// count, and the per-mode quantities in the form of a modes file. These are the steps `mastrom
// modes` takes between reading the configuration and writing the file, in one library function so
// that every caller holding a Config (the Python module) gets the same numbers bit for bit.
#pragma once

#include <string>

#include "common/config.hpp"
#include "modes/modes_file.hpp"

namespace mastrom::modes {

struct MastModes {
  ModesData data;                   ///< what a modes file holds under /modes
  bool equilibrium_solved = false;  ///< a static equilibrium under gravity was solved first
  int dofs = 0, constraints = 0;    ///< size of the locked model
  double solve_time_s = 0.0;        ///< the eigen-solver backend alone, wall
};

/// Solve the modes of `config`. With the SLEPc backend the caller must hold a SlepcSession
/// (modes/slepc_session.hpp); the problem is solved on the session's communicator as the CLI does.
/// Throws InputError for a bad configuration and NumericalError when the eigen-solver did not
/// deliver every requested pair (the message of `mastrom modes`).
MastModes solveMastModes(const Config& config);

}  // namespace mastrom::modes
