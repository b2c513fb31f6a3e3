// Exact discrete-time stepping of one damped modal oscillator under first-order-hold forcing
// (docs/theory.md §4.2):
//     η̈ + 2ζω η̇ + ω² η = f(t),   f linear on each step [t_k, t_k + Δ].
// With x = [η, η̇] and F = [0 1; −ω² −2ζω], g = [0; 1], the exact solution over one step is
//     x_{k+1} = A x_k + B₀ f_k + B₁ f_{k+1},
// A = e^{FΔ}, and with Γ₀ = ∫₀^Δ e^{F(Δ−s)} g ds, Γ₁ = ∫₀^Δ e^{F(Δ−s)} g s ds:
//     B₁ = Γ₁/Δ,  B₀ = Γ₀ − Γ₁/Δ.
// All three come from one 4×4 matrix exponential of the augmented system ż = [F g 0; 0 0 1; 0 0 0] z
// (z = [x; f; ḟ], Van Loan 1978), so rigid (ω = 0), under-, critically and over-damped modes are
// handled alike. Computed once per mode and step size; a step is then 2×2 work.
#pragma once

#include <Eigen/Core>

namespace mastrom::rom {

struct OscillatorStep {
  Eigen::Matrix2d a;   ///< state transition e^{FΔ}
  Eigen::Vector2d b0;  ///< weight of f at the start of the step
  Eigen::Vector2d b1;  ///< weight of f at the end of the step
};

/// Discrete-time matrices for natural frequency ω [rad/s] ≥ 0, damping ratio ζ ≥ 0, step Δ [s] > 0.
OscillatorStep discretizeOscillator(double omega_rad_s, double zeta, double step_s);

/// Advance x = [η, η̇] by one step with forcing f_start → f_end (linear in between).
inline Eigen::Vector2d advance(const OscillatorStep& s, const Eigen::Vector2d& x, double f_start,
                               double f_end) {
  return s.a * x + s.b0 * f_start + s.b1 * f_end;
}

}  // namespace mastrom::rom
