// Modal stress recovery (docs/theory.md §6.5): the interface stresses of a ROM deployment from its
// modal coordinates, in the mode-acceleration form. The shells' strains are invariant under the
// rigid rotation R(θ − θ₀), so with q = R(q̄ + Φη) the plane stresses of every recovery point are,
// to first order in the elastic motion,
//     σ(t) = σ̄ + Σ_k S_k (η_k + μ η̇_k) + Σ_j S_res,j f_j(t),
//   σ̄         the stress of the linearisation state q̄ (the preload; zero without gravity),
//   S_k       the linearised stress per unit of mode k (∂σ/∂q · φ_k at q̄; the Kelvin–Voigt rate
//             term μ ε̇ of the same strains gives μ S_k η̇_k),
//   f_j       the load scalars of the modal forcing (θ̈, θ̇², and the rotating-frame gravity change
//             g_x, g_y: rom/model/modal_stepping.hpp ForcingScalars), whose load vectors are
//             F_θ̈ = −MΩq̄, F_θ̇² = −MΩ²q̄, F_gx = M e_x, F_gy = M e_y,
//   S_res,j   the stress of the static residual K⁻¹F_j − Σ_k φ_k φ_kᵀF_j/ω_k² (constrained K,
//             the modes kept): the quasi-static part of the truncated modes (the static
//             correction of the mode-acceleration method, [CK06] in docs/theory.md).
// The mode-displacement form is the same without S_res; it converges with the number of modes as
// the truncated modes' static share does (measured in docs/user_guide.md).
//
// Per point two stress vectors are stored, each [σ11, σ22, σ12] in the element's local frame
// (fullorder/shell_stress.hpp): the membrane stress σ_m = N/h and the bending stress at the face
// ζ = +h/2, σ_b = 6M/h², so that the three ζ stations of the full order are σ_m − σ_b, σ_m and
// σ_m + σ_b (docs/theory.md eq. 6.5). Every quantity is linear in the mode shapes, so it is stored
// and interpolated with the database like the other modal quantities.
#pragma once

#include <Eigen/Core>

namespace mastrom::rom {

/// Stored stress rows per recovery point: σ_m (3), then σ_b (3).
inline constexpr int kStressRowsPerPoint = 6;
/// The load scalars of the static correction, in ForcingScalars order: θ̈ [rad/s²], θ̇² [rad²/s²],
/// g_x, g_y [m/s²] (the rotating-frame change of gravity).
inline constexpr int kStressLoadCount = 4;

struct ModalStress {
  /// Point offsets of the interfaces (interface I owns points [offsets[I], offsets[I+1])); empty:
  /// the model carries no stresses.
  Eigen::VectorXi interface_offsets;
  Eigen::MatrixXd modes;      ///< S (6P × k) [Pa per unit η, i.e. Pa/(kg^½·m)]
  Eigen::MatrixXd loads;      ///< S_res (6P × kStressLoadCount) [Pa per unit load scalar]
  Eigen::VectorXd preload;    ///< σ̄ (6P) [Pa]
  Eigen::Matrix2Xd points;    ///< per point: axial position from the base edge [m], angle [rad]
  double damping_s = 0.0;     ///< Kelvin–Voigt μ of the shells [s]

  int interfaceCount() const {
    return interface_offsets.size() > 1 ? static_cast<int>(interface_offsets.size()) - 1 : 0;
  }
  int pointCount() const { return static_cast<int>(points.cols()); }
  bool empty() const { return interfaceCount() == 0; }
  /// InputError unless the sizes agree with `modes` modes and (check_values) every value is
  /// finite. Values are checked where stresses enter (extraction, a database file); a model
  /// interpolated from checked samples needs only the sizes (this runs once per deployment).
  void validate(int modes, bool check_values = true) const;
};

}  // namespace mastrom::rom
