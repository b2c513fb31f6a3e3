// The generalized-α step: start, prediction, Newton iteration, acceptance, variable step sizes
// and the state a checkpoint needs (docs/theory.md §5). The factorisations are in
// generalized_alpha_solvers.cpp, the recovered accelerations in generalized_alpha_index1.cpp.
#include "fullorder/generalized_alpha.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "common/error.hpp"
#include "fullorder/generalized_alpha_internal.hpp"
#include "fullorder/two_threads.hpp"

namespace mastrom::fullorder {

using generalized_alpha_detail::maxAbs;

GeneralizedAlpha::GeneralizedAlpha(DaeSystem& system, const GeneralizedAlphaOptions& options)
    : system_(system),
      options_(options),
      solver_(std::make_unique<Solver>()),
      spare_solver_(std::make_unique<Solver>()),
      mass_solver_(std::make_unique<Solver>()) {
  MASTROM_REQUIRE(options.rho_inf >= 0.0 && options.rho_inf <= 1.0, InputError,
                  "simulation.rho_inf = ", options.rho_inf, " is out of range: must be in [0, 1]");
  MASTROM_REQUIRE(options.time_step_s > 0.0 && std::isfinite(options.time_step_s), InputError,
                  "simulation.time_step = ", options.time_step_s, " s must be > 0");
  MASTROM_REQUIRE(options.max_iterations >= 1, InputError,
                  "generalized-alpha: max_iterations = ", options.max_iterations, " must be >= 1");
  const double r = options.rho_inf;
  alpha_m_ = (2.0 * r - 1.0) / (r + 1.0);
  alpha_f_ = r / (r + 1.0);
  gamma_ = 0.5 + alpha_f_ - alpha_m_;
  beta_ = 0.25 * (gamma_ + 0.5) * (gamma_ + 0.5);
  h_ = previous_h_ = options.time_step_s;
  updateStepCoefficients();
}

void GeneralizedAlpha::updateStepCoefficients() {
  beta_prime_ = (1.0 - alpha_m_) / (h_ * h_ * beta_ * (1.0 - alpha_f_));
  gamma_prime_ = gamma_ / (h_ * beta_);
}

void GeneralizedAlpha::setStepSize(double h_s) {
  MASTROM_REQUIRE(std::isfinite(h_s) && h_s > 0.0, NumericalError, "generalized-alpha: step size ",
                  h_s, " s at t = ", state_.time_s, " s must be finite and > 0");
  if (keepsStepSize(h_s)) return;  // bit-for-bit the same steps
  // The pseudo-acceleration a_n is carried over unchanged (docs/theory.md §5.3: rescaling its
  // offset from q̈_n with the step, as a_n ≈ q̈(t_n + Δα h) suggests, made a pendulum with changing
  // steps diverge; unchanged, the order stays 2).
  h_ = h_s;
  updateStepCoefficients();
  ahead_.valid = false;  // predicted with the old step
  // Keep the factorisation of the size left; take the spare if it was made for the new size.
  swapIterationFactors();
  if (iteration_inputs_.valid && std::abs(iteration_inputs_.coefficients.stiffness -
                                          1.0 / beta_prime_) > 1e-12 / beta_prime_) {
    factor_valid_ = false;  // advance() refactorises before the step
  }
}

GeneralizedAlpha::~GeneralizedAlpha() = default;

void GeneralizedAlpha::allocateWorkspace(int n, int m) {
  mass_op_ = MassOperator(system_.massMatrix());
  force_.resize(n);
  residual_.r.resize(n);
  residual_.constraint_force.resize(n);
  phi_.resize(m);
  rhs_.resize(n + m);
  sol_.resize(n + m);
}

void GeneralizedAlpha::initialize(const Eigen::VectorXd& q0, const Eigen::VectorXd& qdot0,
                                  double t0_s) {
  const int n = system_.dofCount(), m = system_.constraintCount();
  forces_at_step_ = -1;
  ahead_.valid = false;
  deferred_ = DeferredIndexOne{};
  MASTROM_REQUIRE(q0.size() == n && qdot0.size() == n, InputError,
                  "generalized-alpha: initial state has ", q0.size(), " coordinates, expected ", n);
  allocateWorkspace(n, m);
  state_.time_s = t0_s;
  start_time_s_ = t0_s;
  step_count_ = 0;
  h_ = previous_h_ = options_.time_step_s;
  updateStepCoefficients();
  before_.valid = false;
  state_.q = q0;
  state_.lambda = Eigen::VectorXd::Zero(m);

  system_.constraints(q0, t0_s, phi_);
  const double phi_norm = maxAbs(phi_);
  MASTROM_REQUIRE(phi_norm <= 1e3 * options_.constraint_tolerance + 1e-9, NumericalError,
                  "generalized-alpha: initial positions violate the constraints, |Phi| = ",
                  phi_norm, " at t = ", t0_s, " s");

  // The saddle matrix [M Φ_qᵀ; Φ_q 0] serves both projections below.
  state_.qdot = qdot0;
  factorizeMassSaddle(q0, state_.qdot, state_.lambda, t0_s);
  factor_valid_ = false;

  // Velocities: mass-orthogonal projection onto Φ_q q̇ = −Φ_t.
  system_.constraintJacobian(q0, t0_s, jac_);
  Eigen::VectorXd vel_rhs(m);
  system_.velocityConstraintRhs(q0, t0_s, vel_rhs);
  rhs_.head(n).setZero();
  rhs_.tail(m) = vel_rhs - jac_ * qdot0;
  solve(*mass_solver_, t0_s, rhs_, sol_, rotated_rhs_);
  state_.qdot = qdot0 + sol_.head(n);

  // Consistent accelerations and multipliers (index-1 system, [LW24] eq. 45).
  system_.forces(q0, state_.qdot, t0_s, force_);
  Eigen::VectorXd acc_rhs(m);
  system_.accelerationConstraintRhs(q0, state_.qdot, t0_s, acc_rhs);
  rhs_.head(n) = force_;
  rhs_.tail(m) = acc_rhs;
  solve(*mass_solver_, t0_s, rhs_, sol_, rotated_rhs_);
  MASTROM_REQUIRE(sol_.allFinite(), NumericalError,
                  "generalized-alpha: non-finite initial accelerations at t = ", t0_s, " s");
  state_.qddot = sol_.head(n);
  state_.lambda = sol_.tail(m);
  state_.pseudo_acceleration = state_.qddot;
  // Empty unless the recovery is on, so a reader can never mistake stale values for current ones.
  state_.qddot_index1.resize(0);
  state_.lambda_index1.resize(0);
  if (options_.recover_index1_accelerations) {
    state_.qddot_index1 = state_.qddot;
    state_.lambda_index1 = state_.lambda;
  }
  acc_rhs_.resize(m);
  last_iterations_ = 0;
  previous_qddot_.resize(0);
  previous_lambda_.resize(0);
}

void GeneralizedAlpha::setState(const DaeState& state) {
  deferred_ = DeferredIndexOne{};
  state_ = state;
  step_count_ = std::llround((state.time_s - start_time_s_) / options_.time_step_s);
  factor_valid_ = false;
  before_.valid = false;
  forces_at_step_ = -1;
  ahead_.valid = false;
  previous_qddot_.resize(0);
  previous_lambda_.resize(0);
}

IntegratorSnapshot GeneralizedAlpha::snapshot() const {
  // A deferred recovery may still renew the mass factorisation: the snapshot would miss it.
  MASTROM_REQUIRE(!deferred_.pending || deferred_.done, Error,
                  "generalized-alpha: snapshot with a deferred index-1 recovery outstanding");
  IntegratorSnapshot s;
  s.state = state_;
  s.start_time_s = start_time_s_;
  s.step_count = step_count_;
  s.last_iterations = last_iterations_;
  s.factor_valid = factor_valid_;
  s.factorizations = factorizations();
  s.iteration = iteration_inputs_;
  s.spare_iteration = spare_inputs_;
  s.spare_factor_valid = spare_valid_;
  s.mass = mass_inputs_;
  s.previous_qddot = previous_qddot_;
  s.previous_lambda = previous_lambda_;
  s.step_size_s = h_;
  s.previous_step_size_s = previous_h_;
  return s;
}

void GeneralizedAlpha::restore(const IntegratorSnapshot& s) {
  const int n = system_.dofCount(), m = system_.constraintCount();
  forces_at_step_ = -1;  // force_ and jac_ do not belong to the restored state
  ahead_.valid = false;
  deferred_ = DeferredIndexOne{};
  const auto sized = [&](const FactorizationInputs& f) {
    return !f.valid || (f.q.size() == n && f.qdot.size() == n && f.lambda.size() == m);
  };
  const DaeState& x = s.state;
  MASTROM_REQUIRE(x.q.size() == n && x.qdot.size() == n && x.qddot.size() == n &&
                      x.pseudo_acceleration.size() == n && x.lambda.size() == m &&
                      sized(s.iteration) && sized(s.mass) && s.mass.valid &&
                      (s.previous_qddot.size() == 0 || s.previous_qddot.size() == n) &&
                      s.previous_lambda.size() == (s.previous_qddot.size() == 0 ? 0 : m),
                  InputError, "generalized-alpha: the saved state does not fit this system (", n,
                  " coordinates, ", m, " constraints)");
  allocateWorkspace(n, m);
  acc_rhs_.resize(m);
  factorizeMassSaddle(s.mass.q, s.mass.qdot, s.mass.lambda, s.mass.time_s);
  // The spare first (factorised in place, then moved aside), then the factorisation in use.
  spare_inputs_ = FactorizationInputs{};
  spare_valid_ = false;
  if (s.spare_iteration.valid && sized(s.spare_iteration)) {
    factorize(s.spare_iteration.q, s.spare_iteration.qdot, s.spare_iteration.lambda,
              s.spare_iteration.time_s, s.spare_iteration.coefficients,
              s.spare_iteration.general_lu);
    swapIterationFactors();
    factor_valid_ = false;
    iteration_inputs_ = FactorizationInputs{};
    spare_valid_ = s.spare_factor_valid;
  }
  if (s.iteration.valid) {
    factorize(s.iteration.q, s.iteration.qdot, s.iteration.lambda, s.iteration.time_s,
              s.iteration.coefficients, s.iteration.general_lu);
  }
  state_ = x;
  start_time_s_ = s.start_time_s;
  step_count_ = s.step_count;
  last_iterations_ = s.last_iterations;
  factor_valid_ = s.factor_valid && s.iteration.valid;
  factorizations_ = s.factorizations;
  mass_factorizations_ = 0;
  iteration_inputs_ = s.iteration;
  mass_inputs_ = s.mass;
  previous_qddot_ = s.previous_qddot;
  previous_lambda_ = s.previous_lambda;
  // Older checkpoints (fixed steps only) carry no step size: the option's.
  h_ = s.step_size_s > 0.0 ? s.step_size_s : options_.time_step_s;
  previous_h_ = s.previous_step_size_s > 0.0 ? s.previous_step_size_s : h_;
  updateStepCoefficients();
  before_.valid = false;
}

StepReport GeneralizedAlpha::step() {
  setStepSize(options_.time_step_s);
  // t_{n+1} = t₀ + (n + 1) h, not a running sum: the record then ends exactly where it should.
  const auto timeOfStep = [&](long long k) {
    return start_time_s_ + static_cast<double>(k) * options_.time_step_s;
  };
  before_.valid = false;
  return guardedAdvance(timeOfStep(step_count_ + 1), timeOfStep(step_count_ + 2));
}

StepReport GeneralizedAlpha::stepTo(double t1_s) {
  MASTROM_REQUIRE(state_.q.size() == system_.dofCount(), InputError,
                  "generalized-alpha: stepTo() before initialize()");
  MASTROM_REQUIRE(std::isfinite(t1_s) && t1_s > state_.time_s, NumericalError,
                  "generalized-alpha: step to t = ", t1_s,
                  " s does not advance from t = ", state_.time_s, " s");
  // A speculative step of another size would swap or invalidate factorisations (setStepSize()),
  // which rejectStep() does not take back: it is left to the run that knows it is wanted.
  if (speculating_ && !keepsStepSize(t1_s - state_.time_s)) throw SpeculationAbandoned();
  before_.valid = true;
  before_.state = state_;
  before_.previous_qddot = previous_qddot_;
  before_.previous_lambda = previous_lambda_;
  before_.step_count = step_count_;
  before_.last_iterations = last_iterations_;
  before_.h = h_;
  before_.previous_h = previous_h_;
  try {
    setStepSize(t1_s - state_.time_s);
    return guardedAdvance(t1_s, t1_s + h_);
  } catch (...) {
    rejectStep();
    throw;
  }
}

void GeneralizedAlpha::rejectStep() {
  MASTROM_REQUIRE(before_.valid, Error, "generalized-alpha: no step to reject");
  // Swapped, not copied: the saved copy is taken again before the next step.
  state_.q.swap(before_.state.q);
  state_.qdot.swap(before_.state.qdot);
  state_.qddot.swap(before_.state.qddot);
  state_.pseudo_acceleration.swap(before_.state.pseudo_acceleration);
  state_.lambda.swap(before_.state.lambda);
  state_.qddot_index1.swap(before_.state.qddot_index1);
  state_.lambda_index1.swap(before_.state.lambda_index1);
  state_.time_s = before_.state.time_s;
  previous_qddot_.swap(before_.previous_qddot);
  previous_lambda_.swap(before_.previous_lambda);
  step_count_ = before_.step_count;
  last_iterations_ = before_.last_iterations;
  h_ = before_.h;
  previous_h_ = before_.previous_h;
  updateStepCoefficients();
  forces_at_step_ = -1;  // force_ and jac_ belong to the rejected state
  ahead_.valid = false;
  before_.valid = false;
}

void GeneralizedAlpha::restartAtDiscontinuity() {
  // Only the histories restart: the predictor's and the pipelined evaluation's. The scheme's own
  // q̈, λ and a stay: its index-3 equations see the drive through Φ(q, t) alone, and θ(t) is
  // continuously differentiable at a breakpoint. (Replacing q̈ and λ by the index-1 right limits was
  // tried: it perturbs the algebraic part of the state, which then rings in the parasitic root and,
  // through the velocities, in the accelerations of the next steps; measured on Scheme 1.)
  previous_qddot_.resize(0);
  previous_lambda_.resize(0);
  ahead_.valid = false;
  before_.valid = false;
}

StepReport GeneralizedAlpha::guardedAdvance(double t1, double t_next) {
  try {
    return advance(t1, t_next);
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    if (what.rfind("generalized-alpha:", 0) == 0) throw;  // already carries the context
    factor_valid_ = false;
    throw NumericalError(detail::concat("generalized-alpha: step to t = ", t1, " s failed: ", what,
                                        "; try a smaller simulation.time_step"));
  }
}

void GeneralizedAlpha::predict(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                               const Eigen::VectorXd& qddot, const Eigen::VectorXd& a,
                               const Eigen::VectorXd& lambda, const Eigen::VectorXd& qddot_before,
                               const Eigen::VectorXd& lambda_before, double ratio,
                               Predictor& out) const {
  // Linear extrapolation q̈_{n+1} = 2q̈_n − q̈_{n−1}, λ_{n+1} = 2λ_n − λ_{n−1} (q̈_{n+1} = q̈_n,
  // λ_{n+1} = λ_n on the first step after a start); `ratio` = h_{n+1}/h_n for unequal steps.
  const double h = h_;
  if (qddot_before.size() == qddot.size() && ratio == 1.0) {
    out.qddot = 2.0 * qddot - qddot_before;
    out.lambda = 2.0 * lambda - lambda_before;
  } else if (qddot_before.size() == qddot.size()) {  // unequal steps: slope per unit time
    out.qddot = qddot + ratio * (qddot - qddot_before);
    out.lambda = lambda + ratio * (lambda - lambda_before);
  } else {
    out.qddot = qddot;
    out.lambda = lambda;
  }
  out.a = (alpha_f_ * qddot + (1.0 - alpha_f_) * out.qddot - alpha_m_ * a) / (1.0 - alpha_m_);
  out.q = q + h * qdot + h * h * ((0.5 - beta_) * a + beta_ * out.a);
  out.qdot = qdot + h * ((1.0 - gamma_) * a + gamma_ * out.a);
}

void GeneralizedAlpha::computeResidual(const Eigen::VectorXd& qddot, const Eigen::VectorXd& lambda,
                                       const Eigen::VectorXd& force, const Eigen::VectorXd& phi,
                                       const SparseMatrix& jac, Residual& out) const {
  Eigen::VectorXd& r = out.r;
  r.resize(qddot.size());
  mass_op_.apply(qddot, r);
  const double inertia_scale = maxAbs(r);
  out.constraint_force.noalias() = jac.transpose() * lambda;
  out.force_scale = std::max({inertia_scale, maxAbs(out.constraint_force), maxAbs(force)});
  r += out.constraint_force;
  r -= force;
  out.phi_norm = maxAbs(phi);
  out.norm = maxAbs(r);
  out.finite = r.allFinite() && phi.allFinite();
}

Eigen::VectorXd GeneralizedAlpha::pseudoAcceleration(const Eigen::VectorXd& qddot) const {
  return (alpha_f_ * state_.qddot + (1.0 - alpha_f_) * qddot -
          alpha_m_ * state_.pseudo_acceleration) /
         (1.0 - alpha_m_);
}

bool GeneralizedAlpha::takeEvaluationAhead(double t1) {
  const Predictor& p = predictor_;
  const bool match = ahead_.valid && ahead_.step == step_count_ + 1 && ahead_.time_s == t1 &&
                     ahead_.q == p.q && ahead_.qdot == p.qdot && ahead_.qddot == p.qddot &&
                     ahead_.lambda == p.lambda;
  ahead_.valid = false;
  if (!match) return false;
  force_.swap(ahead_.force);
  phi_.swap(ahead_.phi);
  jac_.swap(ahead_.jac);
  std::swap(residual_, ahead_.residual);
  ++pipelined_steps_;
  return true;
}

void GeneralizedAlpha::evaluateWithNextPrediction(double t1, double t_next, PairRunner* runner) {
  Predictor& p = predictor_;
  // The predicted state of the next step as it will be if this iterate is accepted (acceptIterate:
  // q̈_n, λ_n become the older point), predicted with this step's size (t_next = t1 + h): a step
  // of another size, or a restart, makes its own evaluation instead.
  const Eigen::VectorXd a1 = pseudoAcceleration(p.qddot);
  predict(p.q, p.qdot, p.qddot, a1, p.lambda, state_.qddot, state_.lambda, 1.0, next_predictor_);
  ahead_.q.swap(next_predictor_.q);
  ahead_.qdot.swap(next_predictor_.qdot);
  ahead_.qddot.swap(next_predictor_.qddot);
  ahead_.lambda.swap(next_predictor_.lambda);
  ahead_.step = step_count_ + 2;
  ahead_.time_s = t_next;
  // Each thread forms its own state's residual after evaluating it.
  const std::function<void()> residual_now = [this] {
    computeResidual(predictor_.qddot, predictor_.lambda, force_, phi_, jac_, residual_);
  };
  const std::function<void()> residual_next = [this] {
    computeResidual(ahead_.qddot, ahead_.lambda, ahead_.force, ahead_.phi, ahead_.jac,
                    ahead_.residual);
  };
  const DaeSystem::Evaluation now{&p.q, &p.qdot, t1, &force_, &phi_, &jac_, &residual_now};
  const DaeSystem::Evaluation next{&ahead_.q,   &ahead_.qdot, ahead_.time_s, &ahead_.force,
                                   &ahead_.phi, &ahead_.jac,  &residual_next};
  ahead_.valid = runner != nullptr ? system_.evaluatePairOn(*runner, now, next)
                                   : system_.evaluatePair(now, next);
}

void GeneralizedAlpha::acceptIterate(double t1, int iterations) {
  Predictor& p = predictor_;
  forces_at_step_ = step_count_ + 1;  // force_, jac_ are at the state accepted now
  Eigen::VectorXd a1 = pseudoAcceleration(p.qddot);
  previous_qddot_.swap(state_.qddot);  // q̈_n, λ_n become the predictor's older point
  previous_lambda_.swap(state_.lambda);
  state_.time_s = t1;
  ++step_count_;
  state_.q.swap(p.q);
  state_.qdot.swap(p.qdot);
  state_.qddot.swap(p.qddot);
  state_.pseudo_acceleration = std::move(a1);
  state_.lambda.swap(p.lambda);
  previous_h_ = h_;
  last_iterations_ = iterations;
  if (options_.recover_index1_accelerations) recoverIndexOneAccelerations();
}

StepReport GeneralizedAlpha::advance(double t1, double t_next) {
  const int n = system_.dofCount(), m = system_.constraintCount();
  MASTROM_REQUIRE(state_.q.size() == n, InputError,
                  "generalized-alpha: step() before initialize()");
  forces_at_step_ = -1;  // force_ and jac_ are overwritten by the iterations below

  Predictor& p = predictor_;
  predict(state_.q, state_.qdot, state_.qddot, state_.pseudo_acceleration, state_.lambda,
          previous_qddot_, previous_lambda_, h_ / previous_h_, p);
  Eigen::VectorXd& qdd1 = p.qddot;
  Eigen::VectorXd& lambda1 = p.lambda;
  Eigen::VectorXd& q1 = p.q;
  Eigen::VectorXd& qd1 = p.qdot;

  const IterationCoefficients coeffs{1.0, gamma_prime_ / beta_prime_, 1.0 / beta_prime_, 1.0};
  StepReport report;
  // Renew the factorisation up front when the previous step struggled, or when the step has
  // changed by more than 10 % since it was formed (K/β′ ∝ h²K: a stale factor would then contract
  // by no better than the change, i.e. cost iterations, on the stiff shell coordinates).
  const double stale_stiffness =
      iteration_inputs_.valid ? iteration_inputs_.coefficients.stiffness : coeffs.stiffness;
  if (!factor_valid_ || last_iterations_ > options_.refactor_after_iterations ||
      std::abs(stale_stiffness - coeffs.stiffness) > 0.1 * coeffs.stiffness) {
    if (speculating_) throw SpeculationAbandoned();
    factorize(q1, qd1, lambda1, t1, coeffs);
    factor_valid_ = true;
    report.refactored = true;
  }
  bool fresh_factor = report.refactored;
  double prev_dq = -1.0, dq_norm = -1.0, phi_norm = 0.0, res_norm = 0.0;
  // A deferred index-1 recovery of the previous state runs on this thread while the system's other
  // threads evaluate the first iterate's element forces (DaeSystem::evaluate), or — pipelined —
  // on the other thread beside the first Newton solve. It reads its own copies of its inputs.
  const std::function<void()> deferred_work = [this] { runDeferredIndexOne(); };
  // During a speculation the other thread runs it (beginSpeculation()).
  const bool run_deferred = !speculating_ && deferred_.pending && !deferred_.done;
  // Pipelined steps (GeneralizedAlphaOptions::pipelined_steps): the previous step evaluated this
  // step's predicted state beside its last iterate. Its values are used only for exactly this
  // state, so the step computes what it would have computed itself, bit for bit.
  // With a pair runner the second evaluation is offered to a thread that is busy with other work
  // at first (the judgement of a speculative step's predecessor): made only once it is free.
  PairRunner* const runner = system_.evaluatesPairsOn() ? pair_runner_ : nullptr;
  const bool pipelined =
      options_.pipelined_steps && (runner != nullptr || system_.evaluatesPairs());
  bool evaluated = pipelined && takeEvaluationAhead(t1);
  const bool recovery_beside_solve = evaluated && run_deferred;
  for (int it = 0; it <= options_.max_iterations; ++it) {
    if (!evaluated) {  // else the pipelined evaluation brought the residual along
      system_.evaluate(q1, qd1, t1, force_, phi_, jac_,
                       it == 0 && run_deferred ? &deferred_work : nullptr);
      computeResidual(qdd1, lambda1, force_, phi_, jac_, residual_);
    }
    evaluated = false;
    const double force_scale = residual_.force_scale;
    phi_norm = residual_.phi_norm;
    res_norm = residual_.norm;
    if (!residual_.finite) break;

    const double q_scale = 1.0 + maxAbs(q1);
    const bool at_roundoff = dq_norm >= 0.0 && dq_norm <= 1e-14 * q_scale;
    // The residual cannot be resolved below what one rounding of the positions changes it by,
    // ε‖q‖∞ max_i ‖∂r_i/∂q‖₂ (see factorize()): while the mast turns slowly the net forces are
    // small, 1e-6 of them lies under that floor, and Newton used to spend a second iteration on
    // round-off (on Scheme 3 in cruise the residual went 6.5e-4 → 3.8e-6 → 1.6e-6 of the
    // force scale, increments 4e-13 → 4e-15 m, i.e. at the last bits of q ~ 0.5 m).
    // That floor is per row (docs/theory.md §5.3c, "What holds the middle of the swing"): the
    // largest row's, taken for every row, let an iterate stop after one correction with the
    // module rows' residual up to ~10² times their own round-off — an error of the soft modes that
    // changes with each step's predictor and stale factorisation, which the step control's
    // velocity estimate read as error (e_v ~ h²) and the relative end angular acceleration
    // carried at 10–300 times its round-off in the middle of a smooth swing. Between the two
    // floors the iterate's own error decides where the run gives a tolerance for it (5.1b).
    const bool phi_resolved = phiWithinTolerances(phi_norm, maxAbs(qdd1), 1.0) ||
                              (phi_norm <= options_.constraint_tolerance &&
                               (at_roundoff || phiAtRoundoff(phi_norm, q_scale)));
    const auto solve_increment = [&] {
      rhs_.head(n) = -residual_.r / beta_prime_;
      rhs_.tail(m) = -phi_;
      solve(*solver_, t1, rhs_, sol_, rotated_rhs_);
    };
    bool increment_solved = false;
    if (it > 0 && phi_resolved) {
      const ResidualLevel level =
          at_roundoff ? ResidualLevel::resolved
                      : residualLevel(options_.force_tolerance * force_scale, maxAbs(q1));
      bool accept = level == ResidualLevel::resolved;
      // Rows within the largest row's floor but not their own: what the iterate still lacks is
      // the next increment, one more solve with the factor in hand and no evaluation. Accepted
      // when that error is below what the step control resolves (IterateTolerance), else applied.
      if (!accept && level == ResidualLevel::within_largest_floor &&
          iterate_tolerance_.velocity_m_s > 0.0 && it < options_.max_iterations) {
        solve_increment();
        increment_solved = true;
        ++iterate_increments_solved_;
        accept = iterateWithinTolerance(maxAbs(sol_.head(n)), dq_norm);
        if (accept) ++iterates_by_tolerance_;
      }
      if (accept) {
        report.constraint_residual = phi_norm;
        acceptIterate(t1, report.iterations);
        return report;
      }
    }
    if (it == options_.max_iterations) break;

    const auto newton_update = [&] {
      if (!increment_solved) solve_increment();
      const auto dq = sol_.head(n);
      dq_norm = maxAbs(sol_.head(n));
      q1 += dq;
      qd1 += gamma_prime_ * dq;
      qdd1 += beta_prime_ * dq;
      lambda1 += beta_prime_ * sol_.tail(m);
      if (options_.correct_constraints) correctConstraints(t1);
    };
    if (it == 0 && recovery_beside_solve) {
      runOnTwoThreads(newton_update, deferred_work, true);
    } else {
      newton_update();
    }
    report.iterations = it + 1;

    // Slow contraction with a stale factorisation: renew it at the current iterate (increments at
    // round-off level contract erratically and say nothing about the matrix). A fresh factor of the
    // symmetric part (factorizeIterationBySchur) that still contracts slowly: the whole matrix's
    // LU.
    if (prev_dq > 0.0 && dq_norm > 1e-12 * q_scale &&
        dq_norm > options_.max_contraction * prev_dq) {
      if (!fresh_factor || solver_->block_ready) {
        if (speculating_) throw SpeculationAbandoned();
        factorize(q1, qd1, lambda1, t1, coeffs, /*general_lu=*/fresh_factor);
        report.refactored = true;
        fresh_factor = true;
      }
    }
    prev_dq = dq_norm;

    if (pipelined && (runner == nullptr || runner->secondThreadFree())) {
      evaluateWithNextPrediction(t1, t_next, runner);
      evaluated = true;
    }
  }
  factor_valid_ = false;
  ahead_.valid = false;
  throw NumericalError(detail::concat(
      "generalized-alpha: Newton did not converge at t = ", t1, " s after ", report.iterations,
      " iterations (|residual|inf = ", res_norm, " N, |Phi|inf = ", phi_norm,
      ", last |dq|inf = ", dq_norm, " m); try a smaller simulation.time_step"));
}

}  // namespace mastrom::fullorder
