// When GeneralizedAlpha's Newton iteration stops (docs/theory.md §5.1, "When Newton stops"): the
// momentum residual against its round-off floors, the error an iterate still carries read as the
// step control reads it, and the constraint residual with its second-order correction.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "common/error.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/generalized_alpha_internal.hpp"

namespace mastrom::fullorder {

using generalized_alpha_detail::maxAbs;

GeneralizedAlpha::ResidualLevel GeneralizedAlpha::residualLevel(double force_tolerance_n,
                                                                double q_max) const {
  if (residual_.norm <= force_tolerance_n) return ResidualLevel::resolved;
  const double ulp_q = std::numeric_limits<double>::epsilon() * q_max;
  // Below the largest row's floor no row can be above its own unless the rows differ.
  if (residual_.norm > ulp_q * residual_per_position_) return ResidualLevel::unresolved;
  const Eigen::VectorXd& r = residual_.r;
  if (row_residual_per_position_.size() != r.size()) return ResidualLevel::resolved;
  for (Eigen::Index i = 0; i < r.size(); ++i)
    if (std::abs(r[i]) > std::max(force_tolerance_n, ulp_q * row_residual_per_position_[i]))
      return ResidualLevel::within_largest_floor;
  return ResidualLevel::resolved;
}

void GeneralizedAlpha::setIterateTolerance(IterateTolerance tolerance) {
  MASTROM_REQUIRE(
      tolerance.velocity_m_s >= 0.0 &&
          static_cast<Eigen::Index>(tolerance.coordinates.size()) == tolerance.weights.size(),
      InputError, "generalized-alpha: iterate tolerance ", tolerance.velocity_m_s,
      " m/s must be >= 0, with one weight per coordinate");
  iterate_tolerance_ = std::move(tolerance);
}

bool GeneralizedAlpha::iterateWithinTolerance(double dq_norm, double previous_dq) const {
  // The iterate lacks the increment Δq in sol_ and what the later increments add; with each
  // contracting by θ = ‖Δq‖/‖Δq_prev‖ that is at most ‖Δq‖/(1 − θ) (a geometric series; Hairer &
  // Wanner, Solving ODEs II, §IV.8). Its velocities then lack γ′ times that (§5.1's velocity
  // update), which the step control reads on the monitored coordinates, weighted by W.
  if (!(previous_dq > 0.0)) return false;
  const double theta = dq_norm / previous_dq;
  if (!(theta < 1.0)) return false;  // not contracting: the increment bounds nothing
  const IterateTolerance& tol = iterate_tolerance_;
  double weighted = 0.0;
  for (std::size_t k = 0; k < tol.coordinates.size(); ++k)
    weighted = std::max(
        weighted, std::abs(tol.weights[static_cast<Eigen::Index>(k)] * sol_[tol.coordinates[k]]));
  return gamma_prime_ * weighted <= (1.0 - theta) * tol.velocity_m_s;
}

void GeneralizedAlpha::correctConstraints(double t1) {
  // Newton's update leaves Φ at the size of the constraints' curvature times the update squared
  // (the rigid modules' unit-vector constraints are quadratic): ~1e-14 m on Scheme 3, which (5.1)
  // reads as 3e-5 of max|q̈| at a 16 µs step and which then cost a second iteration in most steps.
  // Here it is removed at once by the update with the same iteration matrix for the constraint
  // rows alone, [J Gᵀ; G 0] [δq; δμ] = [0; −Φ] (a second-order correction as in SQP methods,
  // Nocedal & Wright 2006 §18.3): no force evaluation, and on the Schur route no solve with the
  // (1,1) block. Its momentum rows are zero, so the force residual changes only at second order.
  // docs/theory.md §5.1.
  const int n = system_.dofCount(), m = system_.constraintCount();
  Predictor& p = predictor_;
  system_.constraints(p.q, t1, phi_correction_);
  const double phi_norm = maxAbs(phi_correction_);
  // Only where the convergence test would not already take it, with a factor 4 of margin.
  if (phiAtRoundoff(phi_norm, 1.0 + maxAbs(p.q)) ||
      phiWithinTolerances(phi_norm, maxAbs(p.qddot), 0.25))
    return;
  rhs_.head(n).setZero();
  rhs_.tail(m) = -phi_correction_;
  solve(*solver_, t1, rhs_, sol_, rotated_rhs_);
  const auto dq = sol_.head(n);
  p.q += dq;
  p.qdot += gamma_prime_ * dq;
  p.qddot += beta_prime_ * dq;
  p.lambda += beta_prime_ * sol_.tail(m);
  ++constraint_corrections_;
}

bool GeneralizedAlpha::phiWithinTolerances(double phi_norm, double qddot_norm,
                                           double margin) const {
  const double kappa = options_.constraint_acceleration_tolerance;
  return phi_norm <= margin * options_.constraint_tolerance &&
         (kappa <= 0.0 || beta_prime_ * phi_norm <= margin * kappa * qddot_norm);
}

bool GeneralizedAlpha::phiAtRoundoff(double phi_norm, double q_scale) {
  return phi_norm <= 8.0 * std::numeric_limits<double>::epsilon() * q_scale;
}

}  // namespace mastrom::fullorder
