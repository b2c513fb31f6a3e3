#include "modes/mast_modes.hpp"

#include "common/error.hpp"
#include "fullorder/mast_config.hpp"
#include "modes/linearize.hpp"
#include "modes/modal_analysis.hpp"

namespace mastrom::modes {

MastModes solveMastModes(const Config& config) {
  const double angle = config.modes.angleRad();
  const fullorder::MastModel model =
      buildLockedMast(fullorder::mastParametersFromConfig(config), angle);
  const Linearization lin = linearizeMast(model);

  EigenSolverOptions solver;
  solver.backend = config.modes.backend;
  solver.count = config.modes.count;
  const ModalAnalysis analysis = analyzeMast(model, lin, solver);
  const EigenResult& eigen = analysis.eigen;
  // A partial result is an error here: a caller without a file to keep the converged pairs in
  // would otherwise receive fewer modes than it asked for without noticing.
  MASTROM_REQUIRE(eigen.ok(), NumericalError, "eigen-solver ", toString(eigen.backend), " ",
                  toString(eigen.status), " (", eigen.converged, " of ", eigen.requested,
                  " pairs): ", eigen.message);

  MastModes result;
  result.data = modesData(analysis, lin, angle);
  result.equilibrium_solved = lin.equilibrium_solved;
  result.dofs = model.dofCount();
  result.constraints = model.constraintCount();
  result.solve_time_s = eigen.solve_time_s;
  return result;
}

}  // namespace mastrom::modes
