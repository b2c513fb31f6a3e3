// Linearisation of the constrained multibody system about a static equilibrium (docs/theory.md
// §3.1): the matrices of the constrained eigenproblem K φ = ω² M φ, G φ = 0, plus the damping
// matrix.
//
// At an equilibrium (q*, λ*) of  F_elastic(q) − Q_ext(q) + Φ_qᵀλ = 0,  Φ(q) = 0  (time and the
// joint lock fixed, q̇ = 0), small motions q = q* + δq obey
//     M δq̈ + C δq̇ + K δq + Gᵀ δλ = 0,   G δq = 0,
// with
//     K = K_t + (Φ_qᵀλ*)_q − K_load     (tangent stiffness; the multiplier term is the geometric
//                                        stiffness of every preloaded constraint: the rigid
//                                        modules' internal constraints and the bilinear edge
//                                        clamps),
//     C = ∂F_damping/∂q̇                 (Kelvin–Voigt, docs/theory.md §2.2; K_d = ∂F_damping/∂q
// vanishes
//                                        at q̇ = 0),
//     M (constant),  G = Φ_q(q*).
// Every block comes from MultibodySystem::assembleIterationMatrix — the same code the Newton
// solvers and the integrator use — with coefficients (c_m, c_d, c_k) = (0, 0, 1) for K and
// (0, 1, 0) for C. Why the multiplier term matters: on the constraint manifold the second variation
// of the total potential Π along a curve q(s) with q'(0) = z is zᵀK_t z + ∇Π·q''(0), and
// ∇Π = −Φ_qᵀλ*, Φ_q q'' = −Φ_qq[z, z] turn the second term into zᵀ(Φ_qᵀλ*)_q z. Dropping it (the
// option MultiplierTerm::Exclude, for demonstrations and tests only) loses, e.g., the whole
// pendulum stiffness of a mass hanging on a rigid link.
//
// Equilibrium: Newton with load stepping (fullorder/static_solver.hpp) from a start state. When the
// system carries no gravity and the generalized forces at the start vanish to round-off (the
// stress-free reference rotated rigidly to θ0), the start state is already the equilibrium with
// λ* = 0, and no factorisation is spent on it (EquilibriumSolve::Auto).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fullorder/mast_model.hpp"
#include "fullorder/multibody_system.hpp"
#include "fullorder/static_solver.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/stability.hpp"

namespace mastrom::modes {

/// Whether K contains the multiplier (geometric) term (Φ_qᵀλ)_q. Include is the linearisation;
/// Exclude exists to show what the term does.
enum class MultiplierTerm { Include, Exclude };

/// When to run the static equilibrium solver.
enum class EquilibriumSolve {
  Auto,    ///< unless gravity is zero and the start state is force-free (see header comment)
  Always,  ///< Newton from the start state
  Never    ///< take the start state as equilibrium with λ* = 0 (caller's responsibility)
};

/// What linearizeMast does about the stability of the equilibrium (modes/stability.hpp).
enum class StabilityPolicy {
  Refuse,  ///< check; an unstable equilibrium is a NumericalError naming the unstable shape
  Record,  ///< check and record it in Linearization::stability (`modes --allow-unstable`)
  Skip     ///< do not check (the report says "not checked")
};

struct LinearizationOptions {
  fullorder::StaticSolverOptions static_solver;  ///< load steps, tolerances, time of evaluation
  EquilibriumSolve equilibrium = EquilibriumSolve::Auto;
  MultiplierTerm multiplier_term = MultiplierTerm::Include;
  StabilityPolicy stability = StabilityPolicy::Refuse;  ///< linearizeMast only
  /// linearizeMast only: from an unstable equilibrium, continue the load to the stable branch
  /// (see linearizeMast); false analyses (or refuses) the first equilibrium found.
  bool continue_load = true;
};

/// The linearised model at an equilibrium.
struct Linearization {
  ConstrainedEigenproblem problem;   ///< K (symmetrised), M, G = Φ_q(q*)
  SparseMatrix damping;              ///< C = ∂F_damping/∂q̇ at q* (n × n, symmetric)
  Eigen::VectorXd q;                 ///< q*: the linearisation point
  Eigen::VectorXd lambda;            ///< λ*: equilibrium multipliers (physical units)
  bool equilibrium_solved = false;   ///< false when the start state was taken as is
  fullorder::StaticResult statics;   ///< the static solve's report (if equilibrium_solved)
  double stiffness_asymmetry = 0.0;  ///< max|K − Kᵀ| / max|K| before symmetrisation
  double linearize_time_s = 0.0;     ///< wall time: equilibrium + assembly
  StabilityReport stability;         ///< filled by linearizeMast (checked = false otherwise)
};

/// Linearise `system` about the static equilibrium reached from `q_start` (it must satisfy the
/// constraints, e.g. the reference rotated to the locked angle). Throws NumericalError when the
/// equilibrium is not found or K is far from symmetric (> 1e-6 relative: a non-conservative load,
/// which the symmetric eigen-solvers cannot treat); InputError on a size mismatch.
Linearization linearize(const fullorder::MultibodySystem& system, const Eigen::VectorXd& q_start,
                        const LinearizationOptions& options = {});

/// Linearise a mast whose joint is locked (MastParameters::lock_angle_rad set): start from the
/// stowed reference rotated to θ0, equilibrium under the model's gravity, then (unless
/// options.stability is Skip) the stability check of modes/stability.hpp, the lowest shape labelled.
///
/// When the equilibrium is unstable, the load is continued instead: Newton is a root finder and,
/// applying all of gravity at once, may land on an unstable equilibrium (a shell that would buckle)
/// which the structure never reaches. Applying gravity in kContinuationSteps equal increments, each
/// solved from the previous equilibrium, follows the loading path as a slow real loading does —
/// past a bifurcation onto the stable branch. If that equilibrium passes the check it is the one
/// linearised, and Linearization::stability.branch says so (with the unstable one it replaces).
/// Measured on the soft, heavy Scheme 3 under gravity at θ0 = 0.5° (docs/user_guide.md): the
/// one-step equilibrium is unstable ('shell n=3', −650.78 Hz); the continued one is stable and its
/// first bending mode, 2.7472 Hz, matches the ringing of the nonlinear full order swung to that
/// angle (2.7476 Hz) to 0.02 %.
/// Throws InputError if the joint is driven rather than locked; NumericalError for an unstable
/// equilibrium under StabilityPolicy::Refuse (needs an active SlepcSession unless Skip).
Linearization linearizeMast(const fullorder::MastModel& model,
                            const LinearizationOptions& options = {});

/// The mast of `params` with its joint locked at `angle_rad` (any lock or drive in `params` is
/// replaced). Throws InputError on bad parameters.
fullorder::MastModel buildLockedMast(fullorder::MastParameters params, double angle_rad);

/// Gravity increments of the load continuation of linearizeMast.
constexpr int kContinuationSteps = 20;

}  // namespace mastrom::modes
