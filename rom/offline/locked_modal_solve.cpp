// The locked-mast modal solve of the ROM (see locked_modal_solve.hpp).
#include "rom/offline/locked_modal_solve.hpp"

#include <algorithm>
#include <chrono>

#include "common/error.hpp"
#include "fullorder/mast_config.hpp"

namespace mastrom::rom {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

LockedModalSolve solveLockedMast(const Config& config, int wanted, int margin,
                                 EigenBackendKind backend, const std::string& where) {
  auto start = Clock::now();
  LockedModalSolve out{
      modes::buildLockedMast(fullorder::mastParametersFromConfig(config), config.modes.angleRad()),
      {}, {}, 0.0, 0.0};
  try {
    out.lin = modes::linearizeMast(out.model);
  } catch (const NumericalError& e) {
    throw NumericalError(where + ": " + e.what());
  }
  out.assembly_s = secondsSince(start);

  start = Clock::now();
  const int available = static_cast<int>(out.lin.problem.dofs() - out.lin.problem.constraints());
  MASTROM_REQUIRE(wanted >= 1 && wanted <= available, InputError, where, ": ", wanted,
                  " modes requested, the model has ", available,
                  " degrees of freedom (allowed: 1 … ", available, ")");
  modes::EigenSolverOptions eo;
  eo.count = std::min(wanted + std::max(margin, 0), available);
  eo.backend = backend;
  eo.communicator = MPI_COMM_SELF;  // every rank its own eigenproblem (ignored by ARPACK, dense)
  out.eigen = modes::solveConstrainedEigenproblem(out.lin.problem, eo);
  out.eigensolve_s = secondsSince(start);
  MASTROM_REQUIRE(out.eigen.ok() && out.eigen.converged >= eo.count, NumericalError, where,
                  ": modal solve ", modes::toString(out.eigen.status), " (", out.eigen.converged,
                  " of ", eo.count, " modes): ", out.eigen.message);
  return out;
}

}  // namespace mastrom::rom
