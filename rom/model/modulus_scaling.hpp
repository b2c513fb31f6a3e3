// The exact dependence of a modal model on Young's modulus E (docs/theory.md §4.4 (e)).
//
// Without gravity the linearisation state is the stress-free reference: q̄ and G do not depend on
// E, the geometric stiffness vanishes (λ* = 0), and E enters the locked mast only through the
// shells' law σ = E·D̂·(ε + μ ε̇) (fullorder/shell_material.hpp; the modules are rigid bodies with
// mass only). So with r = E/E₀
//     K(E) = r K(E₀),   C(E) = r C(E₀),   M, G, q̄ unchanged,
// and the constrained problem (3.2) K φ = ω² M φ, G φ = 0, φᵀMφ = 1 has the same mass-normalised
// modes with ω² scaled by r. Hence, per mode:
//   ω_k        → √r ω_k
//   ζ_k        → √r ζ_k          (ζ = φᵀCφ/(2ω), (3.4): r/√r)
//   Γ, Γ_c, ψ, L, ΦᵀMΩΦ, J, m, c̄, p̄ unchanged (built from Φ, M and q̄ alone, (4.2)–(4.3))
// and of the stresses of (6.9):
//   S_k        → r S_k           (∂σ/∂q · φ_k: σ is linear in E, φ_k unchanged)
//   S_res,j    unchanged         (E·D̂ times the static residual K⁻¹F_j − Σ φφᵀF_j/ω², which
//                                 scales as 1/r: the loads F_j are built from M and q̄)
//   σ̄          unchanged (zero: no preload), μ unchanged.
// With gravity the preload σ̄, its geometric stiffness and q̄ all depend on E, not as a power:
// the scaling does not hold and is refused.
#pragma once

#include "rom/model/modal_model.hpp"

namespace mastrom::rom {

/// `model` (solved at E₀, gravity off) changed to the same mast at E = ratio · E₀, in place.
/// Throws InputError when ratio is not finite and > 0 or the model carries gravity.
void scaleYoungsModulus(ModalModel& model, double ratio);

}  // namespace mastrom::rom
