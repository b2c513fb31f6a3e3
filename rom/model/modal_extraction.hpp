// From a linearised mast and its constrained modes to the ModalModel of the ROM (docs/theory.md
// §4.1): the participations Γ = ΦᵀMΩq̄, Γ_c = ΦᵀMΩ²q̄, L = EMΦ, the end module's rotation and
// displacement per mode, the Coriolis matrix ΦᵀMΩΦ, modal damping ζ_k = φ_kᵀCφ_k/(2ω_k), and the
// rigid data (J, m, c̄, p̄) of the reference configuration.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fullorder/mast_model.hpp"
#include "modes/eigen_solver.hpp"
#include "rom/model/modal_model.hpp"

namespace mastrom::rom {

struct LinearizedModes {
  Eigen::VectorXd q_reference;           ///< q̄: linearisation state (joint locked at θ₀)
  double reference_angle_rad = 0.0;      ///< θ₀
  Eigen::SparseMatrix<double> mass;      ///< M
  Eigen::SparseMatrix<double> damping;   ///< C = ∂F_d/∂q̇ (may be empty: ζ = 0)
  Eigen::VectorXd omega_squared;         ///< ω_k² [rad²/s²], ascending
  Eigen::MatrixXd modes;                 ///< Φ (n × k), ΦᵀMΦ = I, GΦ = 0
  /// The linearisation's K, M, G: given, the interfaces' modal stresses are recovered too
  /// (rom/model/modal_stress_extraction.hpp); null: ModalModel::stress stays empty.
  const modes::ConstrainedEigenproblem* problem = nullptr;
};

/// Reduce the linearised mast to its modal deployment model. `model` supplies the DOF layout (end
/// module, uniform fields) and the gravity vector.
ModalModel extractModalModel(const fullorder::MastModel& model, const LinearizedModes& lin);

}  // namespace mastrom::rom
