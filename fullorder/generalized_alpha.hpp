// Generalized-α time integration of index-3 constrained mechanical systems
// (Arnold & Brüls 2007, "Convergence of the generalized-α scheme for constrained mechanical
// systems"; docs/theory.md §5), with the scaling of Bottasso, Dopico & Trainelli 2008 so the
// iteration matrix stays well conditioned as the step h → 0.
//
// Per step the unknowns are q̈_{n+1} and λ_{n+1}; positions and velocities follow from
//   q_{n+1} = q_n + h q̇_n + h²(½ − β) a_n + h² β a_{n+1}
//   q̇_{n+1} = q̇_n + h(1 − γ) a_n + h γ a_{n+1}
//   (1 − α_m) a_{n+1} + α_m a_n = (1 − α_f) q̈_{n+1} + α_f q̈_n
// and Newton solves M q̈ + Φ_qᵀλ = Q, Φ(q, t) = 0 at t_{n+1}. Newton is written in the position
// increment Δq (Δq̈ = β′Δq, Δq̇ = γ′Δq) with the momentum rows divided by β′ and the multiplier
// increment scaled as Δλ = β′Δλ̃, giving the symmetric O(1) matrix
//   [M + (γ′/β′) C_t + K_t/β′ , Φ_qᵀ ; Φ_q , 0].
// Modified Newton: a factorisation is reused across iterations and steps while Newton contracts
// fast, and renewed when it does not (docs/theory.md §5 welcomes this; it converges to the same
// solution). When the system turns rigidly about Z (DaeSystem::rotationSymmetry: the mast on its
// drive), the reused factorisation is turned to the current drive angle, H(now)⁻¹ ≈ P_δ H(then)⁻¹
// P_δᵀ, so it stays as good as fresh for the whole deployment: on Scheme 3, 2.9 → 1.6 Newton
// iterations per step and ~2 instead of ~4 recovery solves.
// Predictor: (q̈, λ)_{n+1} extrapolated linearly from steps n and n−1 (constant on the first step
// after initialize() or setState()). It only changes where Newton starts, not what it converges to;
// on Scheme 3 it cuts Newton iterations from 2.7 to 2.2 per step (measurements).
// Reported accelerations. The index-3 scheme's own q̈_{n+1} and λ_{n+1} carry an algorithmic
// transient of size O(h·jerk) after every start and every jump of a prescribed acceleration (a
// drive law's θ̈), decaying only like ρ∞ⁿ (Arnold & Brüls 2007, §4: first order unless the start is
// perturbed). For outputs we therefore also recover (q̈, λ) from the index-1 equations
// [M Φ_qᵀ; Φ_q 0][q̈; λ] = [Q; γ] at the converged (q_{n+1}, q̇_{n+1}) — the acceleration the
// equations of motion assign to that state, exactly as an unconstrained generalized-α step would;
// it is second order accurate and free of the transient. The solve reuses a factorisation of the
// same matrix with iterative refinement, so it costs two back-substitutions per recovery (the first
// removes the transient, the second measures what is left: docs/theory.md §5.2). Neither output
// uses the pseudo-acceleration a.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fullorder/dae_system.hpp"
#include "fullorder/mass_operator.hpp"
#include "fullorder/saddle_ldlt.hpp"

namespace mastrom::fullorder {

struct GeneralizedAlphaOptions {
  double time_step_s = 1e-4;
  double rho_inf = 0.9;     ///< spectral radius at infinity, [0, 1]
  int max_iterations = 30;  ///< Newton iterations per step before giving up
  /// Converged when ‖Φ‖∞ ≤ constraint_tolerance and the momentum residual
  /// ‖M q̈ + Φ_qᵀλ − Q‖∞ ≤ force_tolerance · max(‖M q̈‖∞, ‖Φ_qᵀλ‖∞, ‖Q‖∞) — a force criterion,
  /// because a position criterion lets stiff shells (K ~ 10⁸…10¹⁴ N/m) keep force errors of K·tol
  /// in the multipliers, i.e. in the joint force and drive torque. Nothing more can be gained, and
  /// the step is accepted too, when the residual is within its round-off floor ε‖q‖∞
  /// max_i‖∂r_i/∂q‖₂ (one rounding of every position; ∂r/∂q from the factorised iteration matrix)
  /// and every row i within its own, ε‖q‖∞ ‖∂r_i/∂q‖₂ — or, given an IterateTolerance, the
  /// iterate's error read from its next increment is within it — or the Newton increment reaches
  /// round-off (‖Δq‖∞ ≤ 1e-14 (1 + ‖q‖∞)).
  double force_tolerance = 1e-6;
  double constraint_tolerance = 1e-11;
  /// A constraint residual Φ left in the positions reads as an acceleration error of β′‖Φ‖∞
  /// (β′ = (1 − α_m)/(βh²(1 − α_f)), docs/theory.md (5.1)): at a 10 µs step 1e-11 of Φ is 0.3 m/s².
  /// Besides ‖Φ‖∞ ≤ constraint_tolerance a step therefore needs β′‖Φ‖∞ ≤
  /// constraint_acceleration_tolerance · ‖q̈‖∞, or Newton increments at round-off (then Φ is as
  /// small as the positions can resolve). 0 switches this criterion off.
  double constraint_acceleration_tolerance = 1e-6;
  /// After each Newton update, evaluate Φ alone and, where the convergence test would not take it,
  /// remove it with one solve in the constraint rows (docs/theory.md §5.1): most steps then
  /// converge in one iteration instead of two.
  bool correct_constraints = true;
  int refactor_after_iterations = 4;  ///< renew the factorisation when a step needed more
  double max_contraction = 0.3;       ///< renew when ‖Δq_k‖/‖Δq_{k−1}‖ exceeds this
  bool recover_index1_accelerations = true;  ///< fill DaeState::qddot_index1 / lambda_index1
  /// Solve with a factorisation turned to the current angle when the system has a rotation
  /// symmetry (DaeSystem::rotationSymmetry). Only changes the rate of convergence, not the answer.
  bool reuse_across_rotation = true;
  /// Solve with the iteration matrix through the Schur complement of a supernodal Cholesky factor
  /// of its (1,1) block's symmetric part when that block is symmetric to 1e-4 and positive definite
  /// (about twice as fast as the sparse LU; see factorizeIterationBySchur() in the .cpp), else with
  /// the LU. A modified Newton: only changes the rate of convergence, not the answer.
  bool schur_iteration_solver = true;
  /// How the symmetric saddle matrices (that route's, and [M Φ_qᵀ; Φ_q 0] of the index-1 recovery)
  /// are solved: the Schur complement of the (1,1) block, whose dense A⁻¹Gᵀ grows like n·m, or the
  /// LDLᵀ factor of the whole matrix, linear in the modules (fullorder/saddle_ldlt.hpp); by default
  /// whichever makes a solve cheaper. Only changes round-off.
  SaddleRoute saddle_route = SaddleRoute::cheaper;
  /// On a system that evaluates two states at once (DaeSystem::evaluatesPairs: the mast with two
  /// threads), pipeline the steps: evaluate each Newton iterate together with the predictor of the
  /// step after it (that step's first evaluation, kept when the iterate is accepted), and run a
  /// deferred index-1 recovery beside the next step's first Newton solve. The same numbers bit for
  /// bit, in less wall time.
  bool pipelined_steps = true;
};

/// State at t_n: positions, velocities, true and pseudo accelerations, multipliers.
struct DaeState {
  double time_s = 0.0;
  Eigen::VectorXd q, qdot, qddot, pseudo_acceleration, lambda;
  /// (q̈, λ) recovered from the index-1 equations at (q, q̇, t); see the header comment.
  Eigen::VectorXd qddot_index1, lambda_index1;
};

/// Inputs from which a factorisation was formed: the matrix is a pure function of them, so
/// refactorising from them rebuilds the LU factors bit for bit (a restart needs this: with modified
/// Newton the reused factorisation is history that shapes every later iterate).
struct FactorizationInputs {
  bool valid = false;
  double time_s = 0.0;
  Eigen::VectorXd q, qdot, lambda;
  IterationCoefficients coefficients;
  /// Factorised by the sparse LU although the Schur route was available (it had contracted slowly).
  bool general_lu = false;
};

/// Everything that determines the integrator's future steps, for checkpoint/restart
/// (fullorder/checkpoint.hpp): restoring it continues bit-for-bit like the uninterrupted run.
struct IntegratorSnapshot {
  DaeState state;
  double start_time_s = 0.0;
  long long step_count = 0;
  int last_iterations = 0;
  bool factor_valid = false;  ///< the iteration matrix factorisation may be reused
  long factorizations = 0;
  FactorizationInputs iteration;  ///< of the iteration matrix in use
  /// Of the iteration matrix of the step size used before the current one (kept for a return to
  /// that size; variable steps only, else invalid).
  FactorizationInputs spare_iteration;
  bool spare_factor_valid = false;
  FactorizationInputs mass;  ///< of [M Φ_qᵀ; Φ_q 0] in use
  /// (q̈, λ) of the step before state (the predictor's second point); empty when there is none.
  Eigen::VectorXd previous_qddot, previous_lambda;
  /// The step size in use and the one of the step before state (variable steps, stepTo()); both
  /// equal options.time_step_s in a fixed-step run.
  double step_size_s = 0.0, previous_step_size_s = 0.0;
};

/// Thrown by a speculative stepTo() where the step would renew its factorisation
/// (GeneralizedAlpha::beginSpeculation): such a step is taken again once it is known to be wanted.
struct SpeculationAbandoned : std::exception {
  const char* what() const noexcept override { return "speculative step abandoned"; }
};

/// How large a Newton iterate's remaining error may be, read as what the step control judges
/// (docs/theory.md §5.1, "When Newton stops"): the velocity error γ′‖W δq‖∞ of the monitored
/// coordinates, with δq the next Newton increment. Where every row of the residual is within the
/// largest row's round-off floor but not each within its own, the iterate is accepted when that
/// error, bounded through the contraction, is within velocity_m_s; otherwise Newton corrects it.
/// velocity_m_s = 0 (the default, fixed steps): every row within its own floor, always.
struct IterateTolerance {
  std::vector<int> coordinates;  ///< the monitored coordinates (the step control's y and v)
  Eigen::VectorXd weights;       ///< W on them (the step control's)
  double velocity_m_s = 0.0;     ///< the largest velocity error accepted [m/s]
};

struct StepReport {
  int iterations = 0;
  bool refactored = false;
  double constraint_residual = 0.0;  ///< ‖Φ(q_{n+1}, t_{n+1})‖∞ at convergence
};

class GeneralizedAlpha {
public:
  GeneralizedAlpha(DaeSystem& system, const GeneralizedAlphaOptions& options);
  ~GeneralizedAlpha();
  GeneralizedAlpha(const GeneralizedAlpha&) = delete;
  GeneralizedAlpha& operator=(const GeneralizedAlpha&) = delete;

  /// Start at (q0, q̇0, t0): checks Φ(q0) ≈ 0, projects q̇0 onto the velocity constraint, and solves
  /// the index-1 system for consistent q̈0 and λ0 ([LW24] eq. 45). Throws NumericalError on
  /// failure.
  void initialize(const Eigen::VectorXd& q0, const Eigen::VectorXd& qdot0, double t0_s);

  /// Advance one step of options().time_step_s on the fixed grid t₀ + k h. Throws NumericalError
  /// (time, iterations, residuals) when Newton fails.
  StepReport step();

  /// Variable steps (docs/theory.md §5.3). Advance from t_n to t1 > t_n, with the step h = t1 − t_n
  /// (the pseudo-acceleration is carried over unchanged). The state before the step is kept, so
  /// rejectStep() can return to it. Throws NumericalError like step(); the state is then the one
  /// before the step.
  StepReport stepTo(double t1_s);
  /// Return to the state before the last stepTo() (the step's error was too large). The
  /// factorisations in use are kept (modified Newton: they shape only the rate of convergence).
  void rejectStep();
  /// The step the next stepTo(state().time_s + stepSize()) takes.
  double stepSize() const { return h_; }
  /// Set the step of the next steps.
  void setStepSize(double h_s);
  /// Whether setStepSize(h_s) would keep the step in use: h_s differs from it only at the level of
  /// rounding (t_n + h − t_n ≠ h), so nothing changes, the factorisations included.
  bool keepsStepSize(double h_s) const { return std::abs(h_s - h_) <= 1e-9 * h_; }
  /// Restart at a discontinuity of the prescribed motion (a jump of the drive's θ̈ or θ⃛) reached
  /// exactly by the last step: the predictor's extrapolation, which would reach across the jump,
  /// starts again from the current state.
  void restartAtDiscontinuity();

  const DaeState& state() const { return state_; }
  /// Fill state().qddot_index1 / lambda_index1 for the current state (what the option does after
  /// every step); callers that sample outputs sparsely call this only at their output instants.
  void updateIndexOneAccelerations() { recoverIndexOneAccelerations(); }
  /// The same recovery for the current state, computed later: during the next step(), on the
  /// calling thread while the system's other threads evaluate element forces (DaeSystem::evaluate),
  /// or by completeDeferredIndexOne(), whichever comes first. Bit-identical to
  /// updateIndexOneAccelerations(). At most one may be outstanding.
  void deferIndexOneAccelerations();
  bool hasDeferredIndexOne() const { return deferred_.pending; }
  /// The state the deferred recovery was asked for (time, q, q̇, q̈, λ) with its qddot_index1 and
  /// lambda_index1; computes them now if no step() has. The reference stays valid until the next
  /// deferIndexOneAccelerations().
  const DaeState& completeDeferredIndexOne();
  /// Speculative steps (docs/theory.md §5.6): the step after the one just taken, computed on this
  /// thread while another thread completes the deferred recovery of the step just taken and the
  /// step control judges it. Requires a deferred recovery outstanding and the undo record of the
  /// last stepTo(). Until endSpeculation() the deferred recovery is left to
  /// recoverDeferredIndexOne() (the other thread), and a stepTo() that would renew the iteration
  /// factorisation throws SpeculationAbandoned instead (the state is then as before it): all a
  /// speculative step changes can be taken back, so the run is the one without speculation, bit
  /// for bit.
  void beginSpeculation();
  /// Run the outstanding deferred recovery on the calling thread (the other thread of a
  /// speculative step); deferredIndexOneState() then holds its result.
  void recoverDeferredIndexOne();
  /// The state of the deferred recovery with its recovered qddot_index1 and lambda_index1, after
  /// recoverDeferredIndexOne() or completeDeferredIndexOne().
  const DaeState& deferredIndexOneState() const { return deferred_.state; }
  /// Hand the pipelined evaluations of the next step's predictor to `runner` instead of the
  /// system's own threads (nullptr: back to those): a speculative step's single-threaded Newton
  /// evaluations take the judging thread's help once it is free (fullorder/work_offer.hpp). Used
  /// only where the system evaluates pairs through a runner (DaeSystem::evaluatesPairsOn).
  void setPairRunner(PairRunner* runner) { pair_runner_ = runner; }
  /// End a speculation; the deferred recovery must be complete (completeDeferredIndexOne()).
  /// keep = the run without speculation takes that same step next: what the speculative stepTo()
  /// did stands — its step, which rejectStep() then takes back, or the effect of its failure. Else
  /// all of it is taken back and rejectStep() takes back the step before it. Either way the state
  /// the recovery was for carries its recovered values, as after updateIndexOneAccelerations().
  void endSpeculation(bool keep);
  /// Restore a previously saved state (restart); the factorisation is renewed on the next step.
  void setState(const DaeState& state);
  /// The complete integrator state between steps (see IntegratorSnapshot).
  IntegratorSnapshot snapshot() const;
  /// Continue from a snapshot of an integrator of the same system and options: sizes the work space
  /// and refactorises both matrices from their recorded inputs. InputError on a size mismatch.
  void restore(const IntegratorSnapshot& snapshot);
  const GeneralizedAlphaOptions& options() const { return options_; }
  /// Factorisations performed so far (for profiling).
  long factorizations() const { return factorizations_ + mass_factorizations_; }
  /// What the index-1 recoveries cost since construction (for profiling and tests;
  /// docs/theory.md §5.2).
  struct IndexOneStatistics {
    long long recoveries = 0;
    long long solves = 0;          ///< refinement solves, the round-off floor's not included
    long long factorizations = 0;  ///< renewals of [M Φ_qᵀ; Φ_q 0] inside a recovery
    long long floor_solves = 0;    ///< solves that measured the round-off floor
    long long floor_stops = 0;     ///< recoveries stopped on the round-off floor
  };
  const IndexOneStatistics& indexOneStatistics() const { return index1_statistics_; }
  /// True when the iteration matrix factorisation in use is the Schur complement over the
  /// Cholesky factor of its (1,1) block (GeneralizedAlphaOptions::schur_iteration_solver), false
  /// for the sparse LU (or before the first factorisation).
  bool iterationSolveBySchur() const;
  /// Round-off floor of the momentum residual per metre of ‖q‖∞ [N/m]: Newton accepts a residual
  /// below ε‖q‖∞ times this (see force_tolerance). From the iteration matrix in use; 0 before one.
  double residualPerPosition() const { return residual_per_position_; }
  /// The same per momentum row, ‖∂r_i/∂q‖₂ [N/m]: Newton stops only when every row is within
  /// ε‖q‖∞ times its own (or the force tolerance).
  const Eigen::VectorXd& rowResidualPerPosition() const { return row_residual_per_position_; }
  /// Accept iterates whose error, read as the step control reads it, is within `tolerance`
  /// (IterateTolerance; the adaptive run derives it from its step control's scales).
  void setIterateTolerance(IterateTolerance tolerance);
  /// Iterates accepted by the IterateTolerance with rows above their own round-off floor, and
  /// the Newton increments solved to judge them (for profiling).
  long long iteratesAcceptedByTolerance() const { return iterates_by_tolerance_; }
  long long iterateIncrementsSolved() const { return iterate_increments_solved_; }
  /// Steps whose first evaluation came from the previous step's pipelined evaluation
  /// (GeneralizedAlphaOptions::pipelined_steps), for profiling.
  long long pipelinedSteps() const { return pipelined_steps_; }
  /// Newton updates followed by a constraint correction (GeneralizedAlphaOptions::
  /// correct_constraints), for profiling.
  long long constraintCorrections() const { return constraint_corrections_; }

private:
  struct Solver;
  /// step() and stepTo() without the error context: one step to t1; the pipelined evaluation of
  /// the next step is made for t_next (t1 + h on a fixed grid, t1 + h after a stepTo()).
  StepReport advance(double t1, double t_next);
  /// The phases of advance(): the previous step's evaluation of this step's predicted state, taken
  /// when it is for exactly that state (pipelined steps); the evaluation of the current iterate
  /// beside the next step's prediction; the acceptance of the converged iterate as the new state.
  bool takeEvaluationAhead(double t1);
  void evaluateWithNextPrediction(double t1, double t_next, PairRunner* runner);
  void acceptIterate(double t1, int iterations);
  /// The second-order correction of Φ after a Newton update (correct_constraints).
  void correctConstraints(double t1);
  /// Whether ‖Φ‖∞ = phi_norm meets the constraint tolerances, each times `margin`: the absolute
  /// one and (5.1) of docs/theory.md §5.1 against ‖q̈‖∞ = qddot_norm at the current step.
  bool phiWithinTolerances(double phi_norm, double qddot_norm, double margin) const;
  /// Whether Φ is below a few roundings of positions of size q_scale = 1 + ‖q‖∞ (as resolved as
  /// the positions allow).
  static bool phiAtRoundoff(double phi_norm, double q_scale);
  StepReport guardedAdvance(double t1, double t_next);
  /// β′, γ′ of the step h_.
  void updateStepCoefficients();
  /// The mass operator and the per-step vectors for n coordinates and m constraints.
  void allocateWorkspace(int n, int m);
  void recoverIndexOneAccelerations();
  /// The recovery's inputs at the current state (recovery_, recovery_from_accepted_residual_).
  void prepareIndexOneInputs();
  /// The recovery's iterative refinement for state s from those inputs: writes qdd, lam, recovery_
  /// and the mass saddle solver only (calls on the system for rotationAngle() alone), so it may
  /// run beside a Newton solve or an evaluation.
  void refineIndexOne(const DaeState& s, bool from_accepted_residual, Eigen::VectorXd& qdd,
                      Eigen::VectorXd& lam);
  void runDeferredIndexOne();
  /// The round-off floor of a recovered q̈ at iterate (qdd, lam) [m/s²]: ‖q̈ part of H⁻¹ ε s‖∞
  /// for the sizes s of the residual's terms with fixed pseudo-random signs (one solve;
  /// docs/theory.md §5.2). Uses recovery_ like refineIndexOne().
  double indexOneRoundoffFloor(const Eigen::VectorXd& qdd, const Eigen::VectorXd& lam, double t);
  /// sol = H⁻¹ rhs with `solver`'s factorisation, turned from its angle to the angle at t
  /// (`rotated`: work space).
  void solve(Solver& solver, double t, const Eigen::VectorXd& rhs, Eigen::VectorXd& sol,
             Eigen::VectorXd& rotated);
  /// The predictor of the step (of size h_) after a state (q, q̇, q̈, a, λ) whose step before had
  /// (q̈, λ) = (qddot_before, lambda_before) (empty: none) and was `ratio` times shorter: linear
  /// extrapolation of q̈ and λ, and the generalized-α update of a, q and q̇ from it (advance()).
  struct Predictor {
    Eigen::VectorXd qddot, lambda, a, q, qdot;
  };
  void predict(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, const Eigen::VectorXd& qddot,
               const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
               const Eigen::VectorXd& qddot_before, const Eigen::VectorXd& lambda_before,
               double ratio, Predictor& out) const;
  /// The momentum residual r = M q̈ + Φ_qᵀλ − Q at an iterate from its evaluation, with the
  /// norms Newton's convergence test needs.
  struct Residual {
    Eigen::VectorXd r, constraint_force;  ///< r and Φ_qᵀλ
    double force_scale = 0.0;             ///< max(‖M q̈‖∞, ‖Φ_qᵀλ‖∞, ‖Q‖∞)
    double norm = 0.0, phi_norm = 0.0;    ///< ‖r‖∞, ‖Φ‖∞
    bool finite = true;
  };
  void computeResidual(const Eigen::VectorXd& qddot, const Eigen::VectorXd& lambda,
                       const Eigen::VectorXd& force, const Eigen::VectorXd& phi,
                       const SparseMatrix& jac, Residual& out) const;
  /// The pseudo-acceleration a_{n+1} that goes with q̈_{n+1} = qddot after state_ (step n).
  Eigen::VectorXd pseudoAcceleration(const Eigen::VectorXd& qddot) const;
  /// [M Φ_qᵀ; Φ_q 0] at (q, t) — Φ_q from the system, or `jacobian` when given (q̇, λ are recorded
  /// for restarts).
  void factorizeMassSaddle(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                           const Eigen::VectorXd& lambda, double t,
                           const SparseMatrix* jacobian = nullptr);
  void factorize(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                 const Eigen::VectorXd& lambda, double t, const IterationCoefficients& c,
                 bool general_lu = false);
  /// Factorise iter_matrix_ for solves through SchurComplement; false where that route does not
  /// apply (the caller then takes the LU).
  bool factorizeIterationBySchur();

  DaeSystem& system_;
  GeneralizedAlphaOptions options_;
  double alpha_m_, alpha_f_, gamma_, beta_, beta_prime_, gamma_prime_;
  double h_ = 0.0;           ///< step in use [s]
  double previous_h_ = 0.0;  ///< step that reached the current state (predictor's ratio)
  DaeState state_;
  /// The state before the last stepTo(), for rejectStep().
  struct BeforeStep {
    bool valid = false;
    DaeState state;
    Eigen::VectorXd previous_qddot, previous_lambda;
    long long step_count = 0;
    int last_iterations = 0;
    double h = 0.0, previous_h = 0.0;
  } before_;
  /// During a speculation (beginSpeculation()): the undo record of the step before the speculative
  /// one, and whether the factorisation in use was valid when it began.
  bool speculating_ = false;
  BeforeStep speculation_before_;
  bool speculation_factor_valid_ = false;
  std::unique_ptr<Solver> solver_;  ///< iteration matrix
  /// The iteration matrix factorisation of the step size before the current one: a change of
  /// step swaps it with solver_, so alternating between two sizes costs no refactorisation.
  std::unique_ptr<Solver> spare_solver_;
  FactorizationInputs spare_inputs_;
  bool spare_valid_ = false;
  double spare_residual_per_position_ = 0.0;
  Eigen::VectorXd spare_row_residual_per_position_;
  /// Swap the factorisation in use with the spare (setStepSize()).
  void swapIterationFactors();
  std::unique_ptr<Solver> mass_solver_;  ///< [M Φ_qᵀ; Φ_q 0] for the index-1 recovery
  bool factor_valid_ = false;
  int last_iterations_ = 0;
  long factorizations_ = 0;
  double start_time_s_ = 0.0;
  long long step_count_ = 0;
  /// step_count_ at whose acceptance force_ and jac_ were last evaluated (−1: not at any).
  long long forces_at_step_ = -1;
  FactorizationInputs iteration_inputs_, mass_inputs_;  ///< for snapshot()
  /// (q̈, λ) at t_{n−1} for the extrapolating predictor; empty right after a (re)start.
  Eigen::VectorXd previous_qddot_, previous_lambda_;
  MassOperator mass_op_;  ///< M x on xyz triples (set by initialize() and restore())
  bool recovery_from_accepted_residual_ = false;  ///< set by prepareIndexOneInputs()
  /// A deferred index-1 recovery (deferIndexOneAccelerations()).
  struct DeferredIndexOne {
    bool pending = false, done = false, from_accepted_residual = false;
    DaeState state;
  } deferred_;
  /// The index-1 recovery's inputs (Q, Φ_q and the accepted residual at its state) and work space:
  /// its own, so it can run while the next step's Newton iteration uses force_, jac_, rhs_, sol_.
  struct RecoveryBuffers {
    Eigen::VectorXd force, residual, rhs, sol, rotated, floor_rhs, floor_sol;
    SparseMatrix jac;
  } recovery_;
  IndexOneStatistics index1_statistics_;
  /// The first evaluation of step `step`, made by the pipelined step before it at its predicted
  /// state (q, q̇, t) (GeneralizedAlphaOptions::pipelined_steps); used only if the step starts
  /// from exactly that state.
  struct EvaluationAhead {
    bool valid = false;
    long long step = 0;
    double time_s = 0.0;
    Eigen::VectorXd q, qdot, qddot, lambda, force, phi;
    SparseMatrix jac;
    Residual residual;  ///< at the predicted (q̈, λ), computed on the evaluating thread
  } ahead_;
  long long pipelined_steps_ = 0;
  long long constraint_corrections_ = 0;
  PairRunner* pair_runner_ = nullptr;     ///< setPairRunner()
  Predictor predictor_, next_predictor_;  ///< this step's and (pipelined) the next one's
  long mass_factorizations_ = 0;  ///< counted apart: the recovery may factorise beside a solve
  // Work vectors, allocated once.
  Residual residual_;  ///< of the current Newton iterate
  Eigen::VectorXd force_, phi_, rhs_, sol_, acc_rhs_, rotated_rhs_, phi_correction_;
  SparseMatrix jac_, iter_matrix_, mass_jacobian_;
  /// max_i ‖∂r_i/∂q‖₂ of the factorised iteration matrix [N/m]: the residual's round-off floor.
  double residual_per_position_ = 0.0;
  /// The same per momentum row i, ‖∂r_i/∂q‖₂ [N/m]: row i's residual floor is ε‖q‖∞ times it.
  Eigen::VectorXd row_residual_per_position_;
  /// How far the momentum residual of the last computeResidual() is resolved: ‖r‖∞ within
  /// force_tolerance_n [N], or every row within the larger of that and its own round-off floor,
  /// ε q_max ‖∂r_i/∂q‖₂ (one rounding of every position, see factorize()) — resolved; else every
  /// row within the largest row's floor — within_largest_floor; else unresolved.
  enum class ResidualLevel { resolved, within_largest_floor, unresolved };
  ResidualLevel residualLevel(double force_tolerance_n, double q_max) const;
  /// Whether the iterate whose Newton increment (sol_'s position part, of ∞-norm dq_norm) follows
  /// a correction of ∞-norm previous_dq is within iterate_tolerance_ (docs/theory.md §5.1).
  bool iterateWithinTolerance(double dq_norm, double previous_dq) const;
  IterateTolerance iterate_tolerance_;
  long long iterates_by_tolerance_ = 0;
  long long iterate_increments_solved_ = 0;
};

}  // namespace mastrom::fullorder
