// The index-1 recovery's stopping rule (docs/theory.md §5.2): the recovered (q̈, λ) must meet its
// accuracy statement — the error left below max(1e-9 max|q̈|, the round-off floor) — against an
// independent reference, a dense LU of [M Φ_qᵀ; Φ_q 0] refined with long-double residuals, while
// making about two solves per recovery (the error left estimated from the contraction the recovery
// itself measured); and a start from rest under gravity, whose 1e-9 of max|q̈| lies below that
// floor, must not renew the factorisation at every recovery.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "coarse_mast.hpp"
#include "common/config.hpp"
#include "fullorder/deployment_system.hpp"
#include "fullorder/generalized_alpha.hpp"

namespace mastrom::fullorder {
namespace {

using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
using LongVector = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

/// The index-1 system of a state and its reference solution.
struct IndexOneReference {
  Eigen::VectorXd qddot;  ///< H⁻¹ b, LU in long double refined with long-double residuals
  double floor = 0.0;  ///< ‖q̈ part of H⁻¹ (ε s ⊙ ±1)‖∞, s the sizes of the residual's terms
};

IndexOneReference referenceSolve(DaeSystem& system, const DaeState& state) {
  const int n = system.dofCount(), m = system.constraintCount();
  SparseMatrix jac;
  system.constraintJacobian(state.q, state.time_s, jac);
  Eigen::VectorXd force(n), acc(m);
  system.forces(state.q, state.qdot, state.time_s, force);
  system.accelerationConstraintRhs(state.q, state.qdot, state.time_s, acc);
  const Eigen::MatrixXd mass = Eigen::MatrixXd(system.massMatrix());
  const Eigen::MatrixXd g = Eigen::MatrixXd(jac);
  LongMatrix h = LongMatrix::Zero(n + m, n + m);
  h.topLeftCorner(n, n) = mass.cast<long double>();
  h.topRightCorner(n, m) = g.transpose().cast<long double>();
  h.bottomLeftCorner(m, n) = g.cast<long double>();
  LongVector b(n + m);
  b << force.cast<long double>(), acc.cast<long double>();
  const Eigen::PartialPivLU<LongMatrix> lu(h);
  LongVector x = lu.solve(b);
  for (int k = 0; k < 3; ++k) x += lu.solve(LongVector(b - h * x));  // residuals in long double
  IndexOneReference ref;
  ref.qddot = x.head(n).cast<double>();
  // One rounding of every term of the residual, with fixed signs (the derivation of §5.2).
  const Eigen::VectorXd lambda = x.tail(m).cast<double>();
  Eigen::VectorXd s(n + m);
  s.head(n) = force.cwiseAbs() + g.cwiseAbs().transpose() * lambda.cwiseAbs();
  s.tail(m) = acc.cwiseAbs() + g.cwiseAbs() * ref.qddot.cwiseAbs();
  for (int i = 0; i < n + m; ++i)
    s[i] *= ((i * 7 + 3) % 5 < 2 ? -1.0 : 1.0) * std::numeric_limits<double>::epsilon();
  ref.floor = lu.solve(s.cast<long double>()).head(n).cast<double>().cwiseAbs().maxCoeff();
  return ref;
}

TEST(IndexOneRecovery, MeetsItsBoundAgainstARefinedDenseSolveInAboutTwoSolves) {
  // The coarse Scheme 1 mast through its 20 ms ramp into the cruise: the stale factorisation of
  // t = 0 is turned by the rotation symmetry and refined at every step.
  testing::EliminatedTurningMast mast;
  GeneralizedAlphaOptions o = integratorFromConfig(mast.config);
  o.recover_index1_accelerations = true;
  GeneralizedAlpha integrator(mast.reduced, o);
  integrator.initialize(mast.q0, mast.v0, 0.0);
  double worst = 0.0;  // error / bound
  int checked = 0;
  for (int k = 1; k <= 300; ++k) {
    integrator.step();
    if (k % 10 != 0) continue;
    const DaeState& s = integrator.state();
    const IndexOneReference ref = referenceSolve(mast.reduced, s);
    const double error = (s.qddot_index1 - ref.qddot).cwiseAbs().maxCoeff();
    const double bound = std::max(1e-9 * ref.qddot.cwiseAbs().maxCoeff(), ref.floor);
    worst = std::max(worst, error / bound);
    EXPECT_LE(error, bound) << "t = " << s.time_s << " s, floor " << ref.floor;
    ++checked;
  }
  const GeneralizedAlpha::IndexOneStatistics& st = integrator.indexOneStatistics();
  const double per_recovery = static_cast<double>(st.solves) / static_cast<double>(st.recoveries);
  std::printf(
      "[ measured ] %d states: error up to %.3g of the bound; %.3f solves per recovery, "
      "%lld renewals, %lld floor solves\n",
      checked, worst, per_recovery, st.factorizations, st.floor_solves);
  EXPECT_EQ(checked, 30);
  // The first correction removes the integrator's transient, the second verifies it and measures
  // the contraction, which says a third is not needed (it was needed with the rule that waited
  // for a third correction to measure the contraction: 2.9 solves per recovery on Scheme 3).
  EXPECT_LE(per_recovery, 2.1);
}

TEST(IndexOneRecovery, AGravityStartFromRestMeetsItsFloorWithoutRenewals) {
  // The camera mast with its motor profile, started from its static equilibrium under gravity:
  // max|q̈| is small against the weight the constraints carry, and 1e-9 of it lies below the
  // round-off floor (measured: 9–136 times over the first 0.05 s). A recovery judged on max|q̈|
  // alone took its slow round-off corrections for a stale factorisation and renewed it at nearly
  // every recovery (first 0.05 s of `mastrom simulate`: 548 of 566 factorisations).
  const Config c = loadConfig(
      std::string(MASTROM_SOURCE_DIR) + "/configs/camera_mast.toml",
      {"drive.law=table", "drive.table=motor_profile.csv", "simulation.gravity=[0,-9.81,0]"});
  MastModel model = buildMast(mastParametersFromConfig(c));
  DeploymentSystem system(model, true);
  GeneralizedAlphaOptions o = integratorFromConfig(c);
  o.time_step_s = 1e-5;
  o.recover_index1_accelerations = true;
  GeneralizedAlpha integrator(system.dae(), o);
  system.initialize(integrator, true);
  // The start's accelerations are the index-1 solution itself (a fresh factorisation): a recovery
  // there corrects only round-off, which the floor recognises after two solves.
  integrator.updateIndexOneAccelerations();
  const GeneralizedAlpha::IndexOneStatistics start = integrator.indexOneStatistics();
  std::printf("[ measured ] at rest: %lld solves, %lld renewals, %lld floor stops\n", start.solves,
              start.factorizations, start.floor_stops);
  EXPECT_EQ(start.floor_stops, 1);
  EXPECT_EQ(start.factorizations, 0);
  double worst = 0.0, worst_ratio = 0.0;  // error / bound; floor / (1e-9 max|q̈|)
  for (int k = 1; k <= 200; ++k) {
    integrator.step();
    if (k % 40 != 0) continue;
    const DaeState& s = integrator.state();
    const IndexOneReference ref = referenceSolve(system.dae(), s);
    const double target = 1e-9 * ref.qddot.cwiseAbs().maxCoeff();
    const double error = (s.qddot_index1 - ref.qddot).cwiseAbs().maxCoeff();
    worst = std::max(worst, error / std::max(target, ref.floor));
    worst_ratio = std::max(worst_ratio, ref.floor / target);
    EXPECT_LE(error, std::max(target, ref.floor)) << "t = " << s.time_s << " s";
  }
  const GeneralizedAlpha::IndexOneStatistics& st = integrator.indexOneStatistics();
  std::printf(
      "[ measured ] floor up to %.3g times 1e-9 max|q''|; error up to %.3g of the bound; "
      "%lld recoveries, %.3f solves each, %lld renewals, %lld floor solves\n",
      worst_ratio, worst, st.recoveries,
      static_cast<double>(st.solves) / static_cast<double>(st.recoveries), st.factorizations,
      st.floor_solves);
  EXPECT_GT(worst_ratio, 1.0);  // the regime this test is for
  EXPECT_LE(st.factorizations, 2);
}

}  // namespace
}  // namespace mastrom::fullorder
