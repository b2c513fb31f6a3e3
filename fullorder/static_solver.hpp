// Static equilibrium of the multibody system by Newton's method with load stepping
// (docs/theory.md §3 "linearisation point"; the strip benchmarks of the tests).
//
// Equations at load factor s ∈ (0, 1] (gravity and applied loads scaled by s, time fixed):
//   R(q, λ) = F_elastic(q) − s Q_ext(q) + Φ_qᵀλ = 0,   Φ(q, t) = 0.
// Newton step with the exact tangent (MultibodySystem's iteration matrix with c_m = c_d = 0, c_k =
// 1):
//   [ K_t + (Φ_qᵀλ)_q − s K_load   σΦ_qᵀ ] [Δq]     [ R  ]
//   [ σΦ_q                          0     ] [Δμ] = − [ σΦ ],     Δλ = σ Δμ,
// σ a constant row/column scale that brings Φ_q to the size of the stiffness (automatic: the mean
// |diagonal| of the stiffness block at the start). Eigen::SparseLU: analyzePattern once, factorize
// every iteration. Converged when ‖Φ‖_∞ ≤ constraint_tolerance and either
// ‖R‖₂ ≤ force_tolerance · max(‖F_elastic − sQ_ext‖₂, ‖Φ_qᵀλ‖₂, ‖sQ_gravity‖₂) or the last Newton
// correction was at round-off level (‖Δq‖_∞ ≤ 1e-13 max(1, ‖q‖_∞)). A load step that fails
// (iteration limit, non-finite residual, singular matrix) is retried with half the increment; below
// min_load_increment a NumericalError reports the load factor, the iteration and the residuals.
#pragma once

#include <Eigen/Core>

#include "fullorder/multibody_system.hpp"

namespace mastrom::fullorder {

struct StaticSolverOptions {
  int load_steps = 1;                   ///< initial number of equal load increments
  int max_iterations = 30;              ///< Newton iterations per load step
  double force_tolerance = 1e-9;        ///< relative, see header (round-off floor ≈ 1e-10)
  double constraint_tolerance = 1e-12;  ///< absolute on ‖Φ‖_∞ (m, m² or 1 per equation)
  double min_load_increment = 1e-5;     ///< smallest load-factor increment before giving up
  double time_s = 0.0;                  ///< time at which the constraints are evaluated
  double constraint_scale = 0.0;        ///< σ; 0 = automatic
};

struct StaticResult {
  Eigen::VectorXd q;
  Eigen::VectorXd lambda;
  int iterations = 0;           ///< Newton iterations, all load steps
  int load_steps = 0;           ///< accepted load steps
  int rejected_steps = 0;       ///< load steps cut back
  double force_residual = 0.0;  ///< ‖R‖₂ at the solution [N, mixed]
  double relative_force_residual = 0.0;
  double constraint_residual = 0.0;  ///< ‖Φ‖_∞ at the solution
};

/// Solve from the start state (q, λ = 0, or the given λ). Throws NumericalError on failure.
StaticResult solveStatic(const MultibodySystem& system, const Eigen::VectorXd& q_start,
                         const StaticSolverOptions& options = {});
StaticResult solveStatic(const MultibodySystem& system, const Eigen::VectorXd& q_start,
                         const Eigen::VectorXd& lambda_start, const StaticSolverOptions& options);

}  // namespace mastrom::fullorder
