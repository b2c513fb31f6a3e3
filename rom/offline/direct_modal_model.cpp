#include "rom/offline/direct_modal_model.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "fullorder/mast_config.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"
#include "rom/offline/locked_modal_solve.hpp"
#include "modes/mode_basis.hpp"
#include "rom/model/modal_extraction.hpp"

namespace mastrom::rom {
namespace {

/// Pairs solved beyond the request, so that a cluster cut by the count can be completed (the
/// clusters of this model are pairs, docs/theory.md §3).
constexpr int kClusterMarginModes = 2;

}  // namespace

ModalModel directModalModel(const Config& config, int modes) {
  const int wanted = modes > 0 ? modes : config.modes.count;
  MASTROM_REQUIRE(wanted >= 1, InputError, "modes = ", wanted, " must be >= 1");
  const LockedModalSolve solve =
      solveLockedMast(config, wanted, kClusterMarginModes, config.modes.backend, "modal model");
  const modes::Linearization& lin = solve.lin;
  const modes::EigenResult& res = solve.eigen;

  const Eigen::VectorXd& w2 = res.eigenvalues_rad2_s2;
  const int kept = modes::countWithWholeClusters(w2, wanted);

  LinearizedModes lm;
  lm.q_reference = lin.q;
  lm.reference_angle_rad = config.modes.angleRad();
  lm.mass = lin.problem.mass;
  lm.damping = lin.damping;
  lm.problem = &lin.problem;
  lm.omega_squared = w2.head(kept);
  lm.modes = res.modes.leftCols(kept);
  return extractModalModel(solve.model, lm);
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
