// Static response of the linearised, constrained mast (docs/theory.md §6.5): for loads F, the
// displacements u with K u + Gᵀμ = F, G u = 0 — the solution the mode-acceleration stress recovery
// corrects the truncated modal sum with. One sparse LU of the (scaled) saddle matrix [K Gᵀ; G 0]
// serves all load columns.
#pragma once

#include <Eigen/Core>

#include "modes/eigen_solver.hpp"

namespace mastrom::modes {

/// u (n × columns of `loads`). Throws InputError on a size mismatch, NumericalError when the
/// saddle matrix is singular (the constrained stiffness has a zero-energy motion: a free joint).
Eigen::MatrixXd solveConstrainedStatics(const ConstrainedEigenproblem& problem,
                                        const Eigen::MatrixXd& loads);

}  // namespace mastrom::modes
