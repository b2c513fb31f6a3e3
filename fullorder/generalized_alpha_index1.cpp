// The accelerations and multipliers GeneralizedAlpha reports, recovered from the index-1
// equations at each converged state, immediately or deferred beside the next step
// (docs/theory.md §5.2).
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "common/error.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/generalized_alpha_internal.hpp"
#include "fullorder/two_threads.hpp"

namespace mastrom::fullorder {

using generalized_alpha_detail::maxAbs;
using generalized_alpha_detail::recordInputs;

void GeneralizedAlpha::recoverIndexOneAccelerations() {
  MASTROM_REQUIRE(!deferred_.pending, Error,
                  "generalized-alpha: an index-1 recovery is deferred; complete it first");
  prepareIndexOneInputs();
  refineIndexOne(state_, recovery_from_accepted_residual_, state_.qddot_index1,
                 state_.lambda_index1);
}

void GeneralizedAlpha::prepareIndexOneInputs() {
  const Eigen::VectorXd& q = state_.q;
  const double t = state_.time_s;
  // Right after a step's acceptance, force_ and jac_ already hold Q and Φ_q at exactly this state
  // (the converged Newton iterate, evaluated for the convergence test): reuse them — bit-identical
  // values, one force evaluation less per output instant (profile) — and the momentum rows
  // at the integrator's (q̈, λ) are minus the residual Newton accepted.
  // Copied: the recovery may run while the next step's Newton iteration overwrites force_ and jac_.
  recovery_from_accepted_residual_ = forces_at_step_ == step_count_ && step_count_ > 0;
  if (recovery_from_accepted_residual_) {
    recovery_.force = force_;
    recovery_.jac = jac_;
    recovery_.residual = residual_.r;
  } else {
    system_.forces(q, state_.qdot, t, recovery_.force);
    system_.constraintJacobian(q, t, recovery_.jac);
  }
  system_.accelerationConstraintRhs(q, state_.qdot, t, acc_rhs_);
  recovery_.rhs.resize(system_.dofCount() + system_.constraintCount());
}

void GeneralizedAlpha::refineIndexOne(const DaeState& s, bool from_accepted_residual,
                                      Eigen::VectorXd& qdd, Eigen::VectorXd& lam) {
  // Reads recovery_ and acc_rhs_ as prepareIndexOneInputs() left them, and calls on the system only
  // for rotationAngle(): it may run while other threads evaluate element forces or solve.
  const int n = system_.dofCount(), m = system_.constraintCount();
  const double t = s.time_s;
  // Start from the integrator's values at this state (they differ from the answer only by the
  // algorithmic transient and the Newton tolerance; the previous output's recovered values can be a
  // whole high-frequency oscillation away: first corrections of ~100 % of max|q̈| were measured) and
  // refine with the (possibly older) factorisation of the same matrix.
  qdd = s.qddot;
  lam = s.lambda;
  bool fresh = false;
  double prev = -1.0;
  RecoveryBuffers& r = recovery_;
  for (int k = 0; k < 12; ++k) {
    if (k == 0 && from_accepted_residual) {
      r.rhs.head(n) = -r.residual;
    } else {
      r.rhs.head(n) = r.force;
      mass_op_.subtract(qdd, r.rhs.head(n));
      r.rhs.head(n).noalias() -= r.jac.transpose() * lam;
    }
    r.rhs.tail(m) = acc_rhs_;
    r.rhs.tail(m).noalias() -= r.jac * qdd;
    solve(*mass_solver_, t, r.rhs, r.sol, r.rotated);
    qdd += r.sol.head(n);
    lam += r.sol.tail(m);
    const double corr = maxAbs(r.sol.head(n)) / (1e-300 + maxAbs(qdd));
    // Converged: the error left after this correction, the correction times the contraction
    // per solve (measured from the third solve on; the first correction removes the transient),
    // is below 1e-9 of max|q̈| — far below what an output or the step control's third differences
    // resolve (the state itself satisfies the momentum equations only to the Newton tolerance).
    // Until the contraction is known the correction itself must be that small. Stopping on the
    // error left instead of on the last correction (≤ 1e-8, ~1e-10 left) saves a solve in about
    // half the recoveries (Scheme 3, first 0.5 s: 4.05 → 3.56 solves per recovery, its relative
    // end angular acceleration moved by 0.002 % NRMSE, its error being 0.74 %; every output and
    // adaptive step has one).
    // Or stagnating at round-off (unresolved high-frequency content of the state can make some
    // accelerations large, which sets the floor of the relative correction).
    const double left = k >= 2 && prev > 0.0 ? corr * std::min(1.0, corr / prev) : corr;
    if (left <= 1e-9 || (prev > 0.0 && corr < 1e-8 && corr > 0.5 * prev)) return;
    // The first correction removes the transient, it is not a refinement: judge the contraction
    // from the second one on. Renew when it is slower than 0.01 per solve: measured on Scheme 3
    //, the stale factorisation contracts by ~0.03–0.1 while the drive turns, and
    // renewing at 0.01 instead of 0.1 cut the solves per recovery from 5.3 to 3.7 for ~8 % less
    // CPU per step (a factorisation costs about as much as 20 solves).
    if (!fresh && k >= 2 && corr > 0.01 * prev) {
      factorizeMassSaddle(s.q, s.qdot, s.lambda, t, &r.jac);
      fresh = true;
    }
    prev = corr;
  }
  MASTROM_REQUIRE(qdd.allFinite() && lam.allFinite(), NumericalError,
                  "generalized-alpha: non-finite accelerations at t = ", t, " s");
  // Not converged to round-off within the cap: renew and solve once more directly.
  factorizeMassSaddle(s.q, s.qdot, s.lambda, t, &r.jac);
  r.rhs.head(n) = r.force;
  r.rhs.tail(m) = acc_rhs_;
  solve(*mass_solver_, t, r.rhs, r.sol, r.rotated);
  qdd = r.sol.head(n);
  lam = r.sol.tail(m);
}

void GeneralizedAlpha::deferIndexOneAccelerations() {
  MASTROM_REQUIRE(!deferred_.pending, Error,
                  "generalized-alpha: an index-1 recovery is already deferred");
  // Refactorising inside the deferred work must not call the system (other threads may be reading
  // its buffers then): that needs the Schur route, which takes Φ_q as it is.
  if (!mass_solver_->schur) {
    recoverIndexOneAccelerations();
    deferred_.state = state_;
    deferred_.pending = deferred_.done = true;
    return;
  }
  prepareIndexOneInputs();
  deferred_.state.time_s = state_.time_s;
  deferred_.state.q = state_.q;
  deferred_.state.qdot = state_.qdot;
  deferred_.state.qddot = state_.qddot;
  deferred_.state.pseudo_acceleration.resize(0);
  deferred_.state.lambda = state_.lambda;
  deferred_.from_accepted_residual = recovery_from_accepted_residual_;
  deferred_.pending = true;
  deferred_.done = false;
}

void GeneralizedAlpha::runDeferredIndexOne() {
  DaeState& s = deferred_.state;
  refineIndexOne(s, deferred_.from_accepted_residual, s.qddot_index1, s.lambda_index1);
  deferred_.done = true;
}

void GeneralizedAlpha::recoverDeferredIndexOne() {
  MASTROM_REQUIRE(deferred_.pending, Error, "generalized-alpha: no index-1 recovery is deferred");
  if (!deferred_.done) runDeferredIndexOne();
}

void GeneralizedAlpha::beginSpeculation() {
  // A step that recovers its own index-1 values on acceptance would do so beside the other thread's
  // recovery, in the same buffers: speculation is for callers that recover explicitly.
  MASTROM_REQUIRE(
      !speculating_ && deferred_.pending && before_.valid && !options_.recover_index1_accelerations,
      Error,
      "generalized-alpha: a speculation needs a deferred recovery, a step to take back "
      "and recover_index1_accelerations off");
  // The undo record of the step just taken is set aside: the speculative stepTo() writes its own.
  std::swap(before_, speculation_before_);
  before_.valid = false;
  speculation_factor_valid_ = factor_valid_;
  speculating_ = true;
}

void GeneralizedAlpha::endSpeculation(bool keep) {
  MASTROM_REQUIRE(speculating_ && !deferred_.pending, Error,
                  "generalized-alpha: end a speculation after its deferred recovery is complete");
  speculating_ = false;
  const bool taken = before_.valid;  // a stepTo() that failed or was abandoned took itself back
  if (keep && taken) {
    // State n lives on in the undo record of the speculative step: the run without speculation
    // had its recovered values there.
    before_.state.qddot_index1 = deferred_.state.qddot_index1;
    before_.state.lambda_index1 = deferred_.state.lambda_index1;
  } else {
    if (taken) rejectStep();
    // A failed speculative step (Newton) invalidated the factorisation: that stands only when the
    // run without speculation takes the same step next and fails the same way.
    if (!keep) factor_valid_ = speculation_factor_valid_;
    std::swap(before_, speculation_before_);
  }
  speculation_before_.valid = false;
  // And in state_, whether it is state n or a step further (acceptIterate() leaves them alone).
  state_.qddot_index1 = deferred_.state.qddot_index1;
  state_.lambda_index1 = deferred_.state.lambda_index1;
}

const DaeState& GeneralizedAlpha::completeDeferredIndexOne() {
  MASTROM_REQUIRE(deferred_.pending, Error, "generalized-alpha: no index-1 recovery is deferred");
  if (!deferred_.done) runDeferredIndexOne();  // no step since: the inputs are still in place
  deferred_.pending = false;
  return deferred_.state;
}

}  // namespace mastrom::fullorder
