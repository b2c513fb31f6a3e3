// From a linearised mast and its constrained modes to the modal stress data of the ROM
// (rom/model/modal_stress.hpp, docs/theory.md §6.5): the preload stress of q̄, the linearised stress
// of every mode, and the stress of the static residual of each load scalar, at every recovery point
// of every interface — evaluated by the full order's own stress recovery
// (fullorder/interface_stress.hpp), so that both models share one definition of the stresses.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fullorder/mast_model.hpp"
#include "modes/eigen_solver.hpp"
#include "rom/model/modal_stress.hpp"

namespace mastrom::rom {

/// @param problem  K, M, G of the linearisation at q_reference (the static correction solves
///                 with K and G)
/// @param modes    Φ (n × k), mass-normalised, GΦ = 0, with ω² = omega_squared (> 0)
/// Throws InputError on a size mismatch, NumericalError when the static solve fails.
/// The linearised stress rows ∂σ/∂q·v at q_reference (modal_stress.hpp's layout: σ_m then σ_b per
/// recovery point, interfaces in order) of every column v of `vectors` (n × c): 6P × c. Zero rows
/// when the mast has no interface.
Eigen::MatrixXd linearizedStressRows(const fullorder::MastModel& model,
                                     const Eigen::VectorXd& q_reference,
                                     const Eigen::MatrixXd& vectors);

ModalStress extractModalStress(const fullorder::MastModel& model,
                               const modes::ConstrainedEigenproblem& problem,
                               const Eigen::VectorXd& q_reference, const Eigen::MatrixXd& modes,
                               const Eigen::VectorXd& omega_squared);

}  // namespace mastrom::rom
