// Modal analysis of the mast (modes/modal_analysis.hpp; docs/theory.md §3): the three backends
// against each other on a small mast with the checks of STYLE habit 4, forced non-convergence, the
// per-mode quantities against independent computations (damping ratio μω/2, the participation sum
// rule, the rigid moment of inertia, the end rotation from finite rotations), labels, MAC between
// angles, canonical bases of degenerate pairs, and the cross-check with the full-order dynamics.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/error.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/static_solver.hpp"
#include "fullorder/block_rotation.hpp"
#include "modes/modal_analysis.hpp"
#include "modes/modal_quantities.hpp"
#include "tests/modes/mast_fixtures.hpp"

namespace mastrom::modes {
namespace {

using fixtures::kDeg;
using fixtures::kPi;

EigenSolverOptions solverOptions(EigenBackendKind backend, int count) {
  EigenSolverOptions o;
  o.backend = backend;
  o.count = count;
  return o;
}

/// Checks of STYLE habit 4 on every returned pair.
void expectValidModes(const ConstrainedEigenproblem& problem, const ModalAnalysis& a) {
  const EigenResult& r = a.eigen;
  ASSERT_EQ(r.modes.cols(), r.converged);
  if (r.converged == 0) return;
  EXPECT_LE(a.residuals.maxCoeff(), 1e-8) << "‖P(Kφ − ω²Mφ)‖/‖Kφ‖ " << a.residuals.transpose();
  const Eigen::MatrixXd gram = r.modes.transpose() * (problem.mass * r.modes);
  EXPECT_LE((gram - Eigen::MatrixXd::Identity(r.converged, r.converged)).cwiseAbs().maxCoeff(),
            1e-10)
      << "ΦᵀMΦ ≠ I";
  const Eigen::MatrixXd g_phi = problem.constraint_jacobian * r.modes;
  EXPECT_LE(g_phi.cwiseAbs().maxCoeff(), 1e-10) << "Gφ ≠ 0";
}

// ---------------------------------------------------------------------------------------------------
// Backends. Collective SLEPc solves come before any ASSERT (the test also runs under mpirun -n 2,
// tests/cli/modes_cli.cmake).
TEST(MastBackends, ThreeBackendsAgreeOnASmallMast) {
  // Scheme 2, default 2 × 8 rings: 468 DOFs, 248 constraints; exact y/z bending pairs.
  const fullorder::MastModel model = buildLockedMast(fixtures::mastParameters(3), 0.0);
  const Linearization lin = linearizeMast(model);
  const int count = 12;
  const ModalAnalysis dense =
      analyzeMast(model, lin, solverOptions(EigenBackendKind::Dense, count));
  const ModalAnalysis arpack =
      analyzeMast(model, lin, solverOptions(EigenBackendKind::Arpack, count));
  const ModalAnalysis slepc =
      analyzeMast(model, lin, solverOptions(EigenBackendKind::Slepc, count));
  ASSERT_TRUE(dense.eigen.ok()) << dense.eigen.message;
  double worst_frequency = 0.0, worst_shape = 0.0;
  for (const ModalAnalysis* other : {&arpack, &slepc}) {
    ASSERT_TRUE(other->eigen.ok()) << other->eigen.message;
    ASSERT_EQ(other->eigen.converged, count);
    expectValidModes(lin.problem, *other);
    for (int k = 0; k < count; ++k) {
      const double f = dense.eigen.frequencies_hz(k);
      worst_frequency = std::max(worst_frequency, std::abs(other->eigen.frequencies_hz(k) / f - 1));
      // Canonical bases: even the exact pairs agree entry by entry (up to the solver tolerance).
      const double mac =
          std::abs(other->eigen.modes.col(k).dot(lin.problem.mass * dense.eigen.modes.col(k)));
      worst_shape = std::max(worst_shape, std::abs(mac - 1.0));
      EXPECT_EQ(other->labels[static_cast<size_t>(k)], dense.labels[static_cast<size_t>(k)]);
      EXPECT_NEAR(other->participation(k), dense.participation(k),
                  1e-7 * dense.participation.cwiseAbs().maxCoeff());
      EXPECT_NEAR(other->damping_ratio(k), dense.damping_ratio(k), 1e-8 * dense.damping_ratio(k));
      EXPECT_LT((other->end_rotation.row(k) - dense.end_rotation.row(k)).norm(),
                1e-6 * dense.end_rotation.row(k).norm() + 1e-9);
    }
  }
  expectValidModes(lin.problem, dense);
  std::printf(
      "[ measured ] Scheme 2 (%d DOFs): max |f/f_dense - 1| = %.1e, max |1 - |phi^T M "
      "phi_dense|| = %.1e over %d modes, ARPACK and SLEPc\n",
      model.dofCount(), worst_frequency, worst_shape, count);
  EXPECT_LT(worst_frequency, 1e-8);
  EXPECT_LT(worst_shape, 1e-8);
}

TEST(MastBackends, IterationLimitIsReportedNotCrashed) {
  const fullorder::MastModel model = buildLockedMast(fixtures::mastParameters(4), 0.0);
  const Linearization lin = linearizeMast(model);
  std::vector<ModalAnalysis> results;
  for (EigenBackendKind backend : {EigenBackendKind::Slepc, EigenBackendKind::Arpack}) {
    EigenSolverOptions o = solverOptions(backend, 20);
    o.max_iterations = 1;
    o.subspace_dimension = 23;  // too small a basis to converge 20 (+2) pairs in one restart
    results.push_back(analyzeMast(model, lin, o));
  }
  for (const ModalAnalysis& a : results) {
    EXPECT_EQ(a.eigen.status, EigenStatus::NotConverged) << toString(a.eigen.backend);
    EXPECT_FALSE(a.eigen.message.empty());
    EXPECT_LT(a.eigen.converged, 20);
    // Whatever did converge is valid and fully post-processed.
    EXPECT_EQ(a.participation.size(), a.eigen.converged);
    EXPECT_EQ(a.labels.size(), static_cast<std::size_t>(a.eigen.converged));
    expectValidModes(lin.problem, a);
  }
}

// ---------------------------------------------------------------------------------------------------
// Per-mode quantities.
TEST(ModalQuantities, DampingRatioIsMuOmegaOverTwoWithoutPreload) {
  const fullorder::MastParameters p = fixtures::mastParameters(4);
  const fullorder::MastModel model = buildLockedMast(p, 0.0);
  const ModalAnalysis a =
      analyzeMast(model, linearizeMast(model), solverOptions(EigenBackendKind::Dense, 10));
  ASSERT_TRUE(a.eigen.ok());
  for (int k = 0; k < a.eigen.converged; ++k) {
    const double omega = 2.0 * kPi * a.eigen.frequencies_hz(k);
    EXPECT_NEAR(a.damping_ratio(k), 0.5 * p.damping_s * omega, 1e-10 * a.damping_ratio(k));
  }
}

TEST(ModalQuantities, ParticipationSumRuleAndRigidInertia) {
  // All n − m modes of a coarse Scheme 1: Σ Γ_k² must equal the part of the rigid rotation field
  // that null(G) can represent, (M r)ᵀ Z (ZᵀMZ)⁻¹ Zᵀ (M r), r = Ωq₀ — computed here from an
  // independent (LU) null-space basis.
  const fullorder::MastParameters p = fixtures::mastParameters(2, 1, 6);
  const fullorder::MastModel model = buildLockedMast(p, 20.0 * kDeg);
  const Linearization lin = linearizeMast(model);
  const int all = static_cast<int>(lin.problem.dofs() - lin.problem.constraints());
  const ModalAnalysis a = analyzeMast(model, lin, solverOptions(EigenBackendKind::Dense, all));
  ASSERT_TRUE(a.eigen.ok());
  ASSERT_EQ(a.eigen.converged, all);

  const Eigen::MatrixXd g = Eigen::MatrixXd(lin.problem.constraint_jacobian);
  const Eigen::MatrixXd z = Eigen::FullPivLU<Eigen::MatrixXd>(g).kernel();
  ASSERT_EQ(z.cols(), all);
  const Eigen::MatrixXd m = Eigen::MatrixXd(lin.problem.mass);
  const Eigen::VectorXd m_r = m * fullorder::rotationRateField(lin.q);
  const Eigen::VectorXd zt_mr = z.transpose() * m_r;
  const double represented = zt_mr.dot((z.transpose() * m * z).ldlt().solve(zt_mr));
  EXPECT_NEAR(a.participation.squaredNorm(), represented, 1e-9 * represented);
  EXPECT_NEAR(a.effective_mass_fraction.sum(), represented / a.rotational_inertia_kg_m2, 1e-9);
  EXPECT_LT(a.effective_mass_fraction.sum(), 1.0);

  // J = rigid moment of inertia about Z: cubes m d²/6 + m x², thin tubes m (R²/2 + x0² + x0 L +
  // L²/3); the interpolated shell geometry differs from the tube by ~5e-4 (shell element tests).
  const double d = p.module_side_m, L = p.interface_length_m, R = p.interface_radius_m;
  const double m_shell = p.density_kg_m3 * p.interface_thickness_m * 2 * kPi * R * L;
  const double x0 = d / 2;
  const double j_exact = 2 * p.module_mass_kg * d * d / 6 + p.module_mass_kg * (d + L) * (d + L) +
                         m_shell * (R * R / 2 + x0 * x0 + x0 * L + L * L / 3);
  EXPECT_NEAR(a.rotational_inertia_kg_m2, j_exact, 1e-3 * j_exact);
}

TEST(ModalQuantities, PairsSplitIntoDrivenAndUndrivenModesAndEndRotationMatchesFiniteRotation) {
  const fullorder::MastModel model = buildLockedMast(fixtures::mastParameters(4), 0.0);
  const Linearization lin = linearizeMast(model);
  const ModalAnalysis a = analyzeMast(model, lin, solverOptions(EigenBackendKind::Dense, 8));
  ASSERT_TRUE(a.eigen.ok());
  // Scheme 3 at 2 × 8: the labels of the measured spectrum (323, 323, 1581, 1709, 1709, 2617 Hz).
  const std::vector<std::string> expected{"bending-y", "bending-z", "torsion",
                                          "bending-y", "bending-z", "axial"};
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_EQ(a.labels[k], expected[k]) << k + 1;
  EXPECT_NEAR(a.eigen.frequencies_hz(0), 323.39, 0.01);
  // The drive (rotation about Z) excites only the in-plane member of each pair.
  const double gamma_scale = a.participation.cwiseAbs().maxCoeff();
  EXPECT_GT(std::abs(a.participation(0)), 0.5 * gamma_scale);
  EXPECT_LT(std::abs(a.participation(1)), 1e-12 * gamma_scale);
  EXPECT_GT(a.effective_mass_fraction(0), 0.9);

  // ψ = ½ Σ c × δc against the rotation of the NCF frame under a finite ±ε step along φ:
  // δR Rᵀ = [ψ]× to O(ε²).
  const fullorder::RigidModule& body = model.system().body(model.endModule());
  const int offset = model.system().bodyDofOffset(model.endModule());
  for (int k = 0; k < 6; ++k) {
    const double eps = 1e-6 / a.eigen.modes.col(k).cwiseAbs().maxCoeff();
    const fullorder::Vec12 q = lin.q.segment<12>(offset);
    const fullorder::Vec12 dq = a.eigen.modes.col(k).segment<12>(offset);
    const Eigen::Matrix3d w = (body.rotation(q + eps * dq) - body.rotation(q - eps * dq)) /
                              (2 * eps) * body.rotation(q).transpose();
    const Eigen::Vector3d psi(0.5 * (w(2, 1) - w(1, 2)), 0.5 * (w(0, 2) - w(2, 0)),
                              0.5 * (w(1, 0) - w(0, 1)));
    EXPECT_LT((psi - a.end_rotation.row(k).transpose()).norm(),
              1e-7 * a.end_rotation.row(k).norm() + 1e-9)
        << "mode " << k + 1;
    EXPECT_LT((dq.head<3>() - a.end_displacement.row(k).transpose()).norm(), 1e-15);
  }
  // In-plane bending turns the end module about Z, out-of-plane bending about the lateral axis.
  EXPECT_GT(std::abs(a.end_rotation(0, 2)), 1e6 * a.end_rotation.row(0).head<2>().norm());
  EXPECT_GT(std::abs(a.end_rotation(1, 1)), 1e6 * std::abs(a.end_rotation(1, 2)));
}

TEST(ModalQuantities, CanonicalBasisDoesNotDependOnTheBasisTheSolverReturned) {
  const fullorder::MastModel model = buildLockedMast(fixtures::mastParameters(3), 0.4);
  const Linearization lin = linearizeMast(model);
  ModalAnalysisOptions options;
  options.solver = solverOptions(EigenBackendKind::Dense, 6);
  options.end_body = model.endModule();
  options.frame_angle_rad = 0.4;
  const ModalAnalysis reference = runModalAnalysis(model.system(), lin, options);
  ASSERT_TRUE(reference.eigen.ok());
  ASSERT_NEAR(reference.eigen.eigenvalues_rad2_s2(0), reference.eigen.eigenvalues_rad2_s2(1),
              1e-10 * reference.eigen.eigenvalues_rad2_s2(0));
  // Any orthogonal mix of the first pair (and a sign flip) comes back to the same basis.
  EigenResult mixed = reference.eigen;
  const double c = std::cos(0.7), s = std::sin(0.7);
  mixed.modes.col(0) = c * reference.eigen.modes.col(0) + s * reference.eigen.modes.col(1);
  mixed.modes.col(1) = s * reference.eigen.modes.col(0) - c * reference.eigen.modes.col(1);
  const ModalAnalysis again = computeModalQuantities(model.system(), lin, mixed, options);
  EXPECT_LT((again.eigen.modes - reference.eigen.modes).cwiseAbs().maxCoeff(),
            1e-12 * reference.eigen.modes.cwiseAbs().maxCoeff());
}

TEST(ModalQuantities, MacBetweenAnglesIsTheIdentityAfterRotatingBack) {
  const fullorder::MastParameters p = fixtures::mastParameters(3);
  const fullorder::MastModel a_model = buildLockedMast(p, 0.0);
  const fullorder::MastModel b_model = buildLockedMast(p, 60.0 * kDeg);
  const ModalAnalysis a =
      analyzeMast(a_model, linearizeMast(a_model), solverOptions(EigenBackendKind::Dense, 8));
  const ModalAnalysis b =
      analyzeMast(b_model, linearizeMast(b_model), solverOptions(EigenBackendKind::Dense, 8));
  Eigen::MatrixXd b_back(b.eigen.modes.rows(), b.eigen.modes.cols());
  for (int k = 0; k < b.eigen.converged; ++k)
    b_back.col(k) = fullorder::rotateEveryBlock(b.eigen.modes.col(k), fullorder::rotationAboutZ(-60.0 * kDeg));
  const Eigen::MatrixXd mac =
      modalAssuranceCriterion(a.eigen.modes, b_back, a_model.system().massMatrix());
  EXPECT_LT((mac - Eigen::MatrixXd::Identity(8, 8)).cwiseAbs().maxCoeff(), 1e-9);
  // Without rotating back, the in-plane bending mode no longer matches itself.
  const Eigen::MatrixXd raw =
      modalAssuranceCriterion(a.eigen.modes, b.eigen.modes, a_model.system().massMatrix());
  EXPECT_LT(raw(0, 0), 0.9);
}

// ---------------------------------------------------------------------------------------------------
// Cross-check with the full-order dynamics (docs/theory.md §5 integrator on the nonlinear model).
TEST(DynamicsCrossCheck, FirstBendingFrequencyMatchesFreeVibrationOfTheEndModule) {
  // Scheme 1 (2 × 8 rings, μ = 0), locked at θ0 = 0, released at rest from the static deflection
  // under a lateral load (gravity −Y preload, removed at t = 0): in-plane bending dominated by the
  // first bending-y mode. Its frequency is measured from the end module's rotation angle about Z by
  // the zero crossings (linear interpolation) of the signal minus its mean, over whole periods.
  fullorder::MastParameters p = fixtures::mastParameters(2);
  p.damping_s = 0.0;
  fullorder::MastModel model = buildLockedMast(p, 0.0);
  const Linearization lin = linearizeMast(model);
  const ModalAnalysis a = analyzeMast(model, lin, solverOptions(EigenBackendKind::Dense, 4));
  ASSERT_TRUE(a.eigen.ok());
  ASSERT_EQ(a.labels[0], "bending-y");
  const double f_modes = a.eigen.frequencies_hz(0);

  fullorder::MastParameters loaded = p;
  loaded.gravity_m_s2 = Eigen::Vector3d(0.0, -200.0, 0.0);
  const fullorder::MastModel preload = buildLockedMast(loaded, 0.0);
  const fullorder::StaticResult eq =
      fullorder::solveStatic(preload.system(), preload.rotatedReference(0.0));

  fullorder::GeneralizedAlphaOptions o;
  o.rho_inf = 0.9;
  o.time_step_s = 1e-5;  // 60 steps per period of the 1.66 kHz mode: period error ≈ (ωh)²/12 ≈ 1e-3
  fullorder::GeneralizedAlpha integrator(model.system(), o);
  integrator.initialize(eq.q, Eigen::VectorXd::Zero(model.dofCount()), 0.0);
  const fullorder::RigidModule& end = model.system().body(model.endModule());
  const int offset = model.system().bodyDofOffset(model.endModule());
  auto endAngle = [&](const Eigen::VectorXd& q) {
    const Eigen::Matrix3d r = end.rotation(q.segment<12>(offset));
    return std::atan2(r(1, 0), r(0, 0));
  };
  const int steps = 800;  // ≈ 13 periods
  std::vector<double> t{0.0}, angle{endAngle(integrator.state().q)};
  for (int i = 0; i < steps; ++i) {
    integrator.step();
    t.push_back(integrator.state().time_s);
    angle.push_back(endAngle(integrator.state().q));
  }
  double mean = 0.0;
  for (double v : angle) mean += v / angle.size();
  std::vector<double> upward;  // upward zero crossings
  for (std::size_t i = 1; i < angle.size(); ++i) {
    const double a0 = angle[i - 1] - mean, a1 = angle[i] - mean;
    if (a0 < 0.0 && a1 >= 0.0) upward.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-a0) / (a1 - a0));
  }
  ASSERT_GE(upward.size(), 10u);
  const double f_dynamics = (upward.size() - 1) / (upward.back() - upward.front());
  std::printf(
      "[ measured ] first bending: modes %.3f Hz, free vibration %.3f Hz (%+.3f %%), %zu "
      "periods\n",
      f_modes, f_dynamics, 100.0 * (f_dynamics / f_modes - 1.0), upward.size() - 1);
  EXPECT_NEAR(f_dynamics, f_modes, 0.01 * f_modes);
}

}  // namespace
}  // namespace mastrom::modes
