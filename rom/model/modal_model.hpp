// The modal deployment model of docs/theory.md §4.1: everything a ROM deployment needs, reduced to
// a few numbers per mode. Built once from the linearised mast (mass matrix M, reference
// configuration q̄ at the linearisation angle θ₀, constrained mass-normalised modes Φ with GΦ = 0).
//
// Kinematics. Every 3-block of q (positions, slopes, NCF vectors) rotates alike, so with the rigid
// rotation R(θ − θ₀) about Z and the elastic part u = Φη in the rotating frame,
//     q = R (q̄ + Φη),      Ω = blockdiag([Z]×),  ΩR = RΩ,  MR = RM (M is N ⊗ I₃ blockwise).
// The driving constraint becomes the locked joint of the linearisation in that frame, so GΦ = 0
// keeps holding. Substituting into M q̈ + Gᵀλ + F_int = F_ext and projecting on Φ (docs/theory.md
// §4.1):
//     η̈ + 2ζω η̇ + ω² η = −Γ θ̈ − Γ_c θ̇² − 2θ̇ (ΦᵀMΩΦ) η̇ + Lᵀ (Rᵀ g − g₀),
//     Γ = ΦᵀMΩq̄,  Γ_c = ΦᵀMΩ²q̄,  L = E M Φ  (E: the three uniform unit fields),
// g₀ = the gravity the preload at θ₀ already balances. Outputs, all linear in (η, η̇, η̈) plus the
// rigid motion (derivations in modal_deployment.cpp):
//   end angular acceleration  α = θ̈ Z + R ψ η̈ + θ̇ Z × (R ψ η̇)      (ψ: end rotation per unit η)
//   linear momentum           P = R[θ̇ Z × (m c̄ + Lη) + Lη̇]          → joint force Ṗ − m g
//   angular momentum about Z  H = θ̇ (J − 2Γ_cᵀη) + Γᵀη̇             → drive torque Ḣ − τ_gravity
// Damping: Kelvin–Voigt C = μ K_material, so ζ_k = φ_kᵀCφ_k/(2ω_k) (= μω_k/2 without preload).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "rom/model/modal_stress.hpp"

namespace mastrom::rom {

struct ModalModel {
  // Per mode k (columns / entries in ascending frequency).
  Eigen::VectorXd omega_rad_s;         ///< ω_k
  Eigen::VectorXd damping_ratio;       ///< ζ_k
  Eigen::VectorXd rotation_participation;     ///< Γ_k [kg^½·m]
  Eigen::VectorXd centrifugal_participation;  ///< Γ_c,k [kg^½·m]
  Eigen::Matrix3Xd end_rotation;      ///< ψ (3 × k): end-module small rotation per unit η [rad/(kg^½·m)]
  Eigen::Matrix3Xd end_translation;   ///< end-module centroid displacement per unit η
  Eigen::Matrix3Xd momentum_participation;  ///< L = E M Φ (3 × k) [kg^½]
  Eigen::MatrixXd coriolis;           ///< ΦᵀMΩΦ (k × k, skew-symmetric)

  // Rigid data of the reference configuration q̄ (frame of the linearisation angle θ₀).
  double inertia_z_kg_m2 = 0.0;       ///< J = (Ωq̄)ᵀ M (Ωq̄)
  double total_mass_kg = 0.0;
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();      ///< c̄ of the whole mast
  Eigen::Vector3d end_position_m = Eigen::Vector3d::Zero();  ///< p̄, end-module centroid
  double reference_angle_rad = 0.0;   ///< θ₀
  Eigen::Vector3d gravity_m_s2 = Eigen::Vector3d::Zero();    ///< global g

  /// The interfaces' modal stresses (docs/theory.md §6.5); empty when not recovered. Not one of the
  /// fields below: its row count follows the mesh, not the modes (stored in its own group of a
  /// database file, rom/database/database_io.hpp).
  ModalStress stress;

  int modeCount() const { return static_cast<int>(omega_rad_s.size()); }
  /// Every per-mode field sized for k modes (values unset); the Coriolis matrix k × k with
  /// `coriolis_matrix`, else empty.
  void resizeModes(Eigen::Index k, bool coriolis_matrix);
  /// Throws InputError if the sizes disagree or a value is not finite.
  void validate() const;
};

/// The model restricted to `modes` (indices into m's modes, in the order given): every per-mode
/// field sliced, the Coriolis matrix to its sub-block, the rigid data copied. The modal stresses
/// are dropped (their rows mix all modes' recovery; the callers need none). InputError on an
/// index out of range.
ModalModel selectModes(const ModalModel& m, const std::vector<int>& modes);

/// The modes of every part side by side, in order, with the rigid data of the first and no Coriolis
/// matrix: uncoupled oscillators stepped as one model (rom/offline/leave_one_out.hpp). InputError
/// when `parts` is empty.
ModalModel concatenateModes(const std::vector<ModalModel>& parts);

/// How the size of a ModalModel field follows the mode count k.
enum class ModalFieldShape {
  Scalar,          ///< one number
  Vector3,         ///< 3
  PerMode,         ///< k
  Vector3PerMode,  ///< 3 × k
  ModeByMode,      ///< k × k (may also be empty: no Coriolis coupling)
};

struct ModalFieldInfo {
  const char* name;  ///< dataset name in ROM database files
  ModalFieldShape shape;
  const char* units;
};

/// Calls visit(info, member) for every field of `m` (a ModalModel, const or not), in the one order
/// that the database file, its checksum, the MPI gather of a build and the size checks all follow.
/// `member` is a double, Eigen::Vector3d, Eigen::VectorXd, Eigen::Matrix3Xd or Eigen::MatrixXd.
/// A new field of the model is one line here, plus its meaning in the interpolators.
template <class Model, class Visit>
void forEachModalField(Model& m, Visit&& visit) {
  using S = ModalFieldShape;
  visit(ModalFieldInfo{"omega", S::PerMode, "rad/s"}, m.omega_rad_s);
  visit(ModalFieldInfo{"damping_ratio", S::PerMode, "1"}, m.damping_ratio);
  visit(ModalFieldInfo{"rotation_participation", S::PerMode, "kg^0.5*m"},
        m.rotation_participation);
  visit(ModalFieldInfo{"centrifugal_participation", S::PerMode, "kg^0.5*m"},
        m.centrifugal_participation);
  visit(ModalFieldInfo{"end_rotation", S::Vector3PerMode, "rad/(kg^0.5*m)"}, m.end_rotation);
  visit(ModalFieldInfo{"end_translation", S::Vector3PerMode, "kg^-0.5"}, m.end_translation);
  visit(ModalFieldInfo{"momentum_participation", S::Vector3PerMode, "kg^0.5"},
        m.momentum_participation);
  visit(ModalFieldInfo{"coriolis", S::ModeByMode, "1"}, m.coriolis);
  visit(ModalFieldInfo{"inertia_z", S::Scalar, "kg*m^2"}, m.inertia_z_kg_m2);
  visit(ModalFieldInfo{"total_mass", S::Scalar, "kg"}, m.total_mass_kg);
  visit(ModalFieldInfo{"centroid", S::Vector3, "m"}, m.centroid_m);
  visit(ModalFieldInfo{"end_position", S::Vector3, "m"}, m.end_position_m);
  visit(ModalFieldInfo{"reference_angle", S::Scalar, "rad"}, m.reference_angle_rad);
  visit(ModalFieldInfo{"gravity", S::Vector3, "m/s^2"}, m.gravity_m_s2);
}

}  // namespace mastrom::rom
