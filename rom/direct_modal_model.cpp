#include "rom/direct_modal_model.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "fullorder/mast_config.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"
#include "rom/modal_extraction.hpp"

namespace mastrom::rom {
namespace {

/// Pairs solved beyond the request, so that a cluster cut by the count can be completed (the
/// clusters of this model are pairs, DESIGN §3).
constexpr int kClusterMarginModes = 2;

}  // namespace

ModalModel directModalModel(const Config& config, int modes) {
  const int wanted = modes > 0 ? modes : config.modes.count;
  MASTROM_REQUIRE(wanted >= 1, InputError, "modes = ", wanted, " must be >= 1");
  const fullorder::MastModel model =
      modes::buildLockedMast(fullorder::mastParametersFromConfig(config), config.modes.angleRad());
  const modes::Linearization lin = modes::linearizeMast(model);

  const int available = static_cast<int>(lin.problem.dofs() - lin.problem.constraints());
  MASTROM_REQUIRE(wanted <= available, InputError, "modes = ", wanted, " requested, the model has ",
                  available, " degrees of freedom");
  modes::EigenSolverOptions eo;
  eo.count = std::min(wanted + kClusterMarginModes, available);
  eo.backend = config.modes.backend;
  eo.communicator = MPI_COMM_SELF;  // one case, one process
  const modes::EigenResult res = modes::solveConstrainedEigenproblem(lin.problem, eo);
  MASTROM_REQUIRE(res.ok() && res.converged >= eo.count, NumericalError, "modal solve ",
                  modes::toString(res.status), " (", res.converged, " of ", eo.count,
                  " modes): ", res.message);

  const Eigen::VectorXd& w2 = res.eigenvalues_rad2_s2;
  int kept = wanted;
  while (kept < eo.count &&
         std::abs(w2[kept] - w2[kept - 1]) <= kDirectClusterTolerance * std::abs(w2[kept]))
    ++kept;

  LinearizedModes lm;
  lm.q_reference = lin.q;
  lm.reference_angle_rad = config.modes.angleRad();
  lm.mass = lin.problem.mass;
  lm.damping = lin.damping;
  lm.omega_squared = w2.head(kept);
  lm.modes = res.modes.leftCols(kept);
  return extractModalModel(model, lm);
}

int firstExcitedMode(const ModalModel& model) {
  if (model.modeCount() == 0) return -1;
  const double largest = model.rotation_participation.cwiseAbs().maxCoeff();
  if (!(largest > 0)) return -1;
  for (int k = 0; k < model.modeCount(); ++k)
    if (std::abs(model.rotation_participation[k]) >= 1e-3 * largest) return k;
  return -1;
}

}  // namespace mastrom::rom
