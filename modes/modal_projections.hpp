// The per-mode quantities of the modal deployment model, computed in one place for the modal
// analysis (modes/modal_analysis.hpp) and the ROM (rom/model/modal_extraction.hpp).
//
// With mass-normalised constrained modes Φ (ΦᵀMΦ = I, GΦ = 0) of a linearisation at q̄ and the
// rigid rotation field Ωq̄ = Z × (every 3-block of q̄) (docs/theory.md (4.1)–(4.3), (3.4)):
//   ω_k = √max(ω_k², 0),   ζ_k = max(φ_kᵀCφ_k, 0) / (2ω_k)  (0 for ω_k = 0 or no C),
//   Γ = (MΦ)ᵀ Ωq̄,   Γ_c = (MΦ)ᵀ Ω²q̄,   L = EMΦ (3 × k, E the uniform unit fields),
//   ΦᵀMΩΦ (k × k, skew),   J = (Ωq̄)ᵀ M (Ωq̄),
//   the end module's small rotation ½ Σ_c c × δc over its frame columns c = x̂, u, v and its
//   centroid displacement, per unit modal coordinate (3 × k each).
#pragma once

#include <Eigen/Core>

#include "fullorder/multibody_system.hpp"
#include "modes/eigen_solver.hpp"

namespace mastrom::modes {

struct ModalProjections {
  Eigen::VectorXd omega_rad_s;                ///< ω [rad/s]
  Eigen::VectorXd damping_ratio;              ///< ζ [1]
  Eigen::VectorXd rotation_participation;     ///< Γ [√kg·m]
  Eigen::VectorXd centrifugal_participation;  ///< Γ_c [√kg·m]
  Eigen::Matrix3Xd translation_participation; ///< L [√kg]
  Eigen::MatrixXd coriolis;                   ///< ΦᵀMΩΦ [1]
  Eigen::Matrix3Xd end_rotation;              ///< [rad/(√kg·m)]; zero without an end body
  Eigen::Matrix3Xd end_translation;           ///< [1/√kg]; zero without an end body
  double inertia_z_kg_m2 = 0.0;               ///< J
};

/// The quantities of the header comment. `damping` may be empty (ζ = 0); `end_body` = −1 for none.
/// Throws InputError when the sizes of the inputs disagree.
ModalProjections projectModes(const fullorder::MultibodySystem& system, const SparseMatrix& mass,
                              const SparseMatrix& damping, const Eigen::VectorXd& q_reference,
                              const Eigen::VectorXd& omega_squared, const Eigen::MatrixXd& modes,
                              int end_body);

}  // namespace mastrom::modes
