// Linearisation about a locked deployment angle (modes/linearize.hpp; docs/theory.md §3): the
// blocks K, M, G, C against their definitions and physical invariants, the static equilibrium under
// gravity, and the multiplier (geometric) term (Φ_qᵀλ)_q against an independent reference — the
// curvature of the total potential along the constraint manifold, by finite differences — including
// the angle dependence of the frequencies that in-plane gravity causes (and that only the full
// tangent predicts).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "fullorder/block_rotation.hpp"
#include "modes/linearize.hpp"
#include "modes/modal_analysis.hpp"
#include "tests/modes/mast_fixtures.hpp"

namespace mastrom::modes {
namespace {

using fixtures::kDeg;

double maxAbs(const SparseMatrix& a) {
  double m = 0.0;
  for (Eigen::Index k = 0; k < a.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) m = std::max(m, std::abs(it.value()));
  return m;
}

EigenSolverOptions dense(int count) {
  EigenSolverOptions o;
  o.backend = EigenBackendKind::Dense;
  o.count = count;
  return o;
}

TEST(Linearize, StressFreeStateGivesConsistentBlocksAndKelvinVoigtDamping) {
  const fullorder::MastParameters p = fixtures::mastParameters(2);
  const fullorder::MastModel model = buildLockedMast(p, 0.3);
  const Linearization lin = linearizeMast(model);
  const int n = model.dofCount(), m = model.constraintCount();

  // No gravity: the rotated reference is the equilibrium, with zero multipliers, and no Newton.
  EXPECT_FALSE(lin.equilibrium_solved);
  EXPECT_EQ(lin.lambda.size(), m);
  EXPECT_EQ(lin.lambda.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT((lin.q - model.rotatedReference(0.3)).cwiseAbs().maxCoeff(), 1e-15);

  ASSERT_EQ(lin.problem.stiffness.rows(), n);
  ASSERT_EQ(lin.problem.mass.rows(), n);
  ASSERT_EQ(lin.problem.constraint_jacobian.rows(), m);
  ASSERT_EQ(lin.problem.constraint_jacobian.cols(), n);
  ASSERT_EQ(lin.damping.rows(), n);
  EXPECT_NO_THROW(lin.problem.validate());
  EXPECT_LT(lin.stiffness_asymmetry, 1e-12);
  EXPECT_EQ(maxAbs(SparseMatrix(lin.problem.mass - model.system().massMatrix())), 0.0);
  SparseMatrix g;
  model.system().constraintJacobian(lin.q, 0.0, g);
  EXPECT_EQ(maxAbs(SparseMatrix(lin.problem.constraint_jacobian - g)), 0.0);

  // Stress-free Kelvin–Voigt: C = μ K exactly (both are h D-weighted strain Gram matrices).
  const double mu = p.damping_s;
  EXPECT_LT(maxAbs(SparseMatrix(lin.damping - mu * lin.problem.stiffness)),
            1e-12 * mu * maxAbs(lin.problem.stiffness));

  // Rigid motions of the whole model cost no strain energy at a stress-free state: K annihilates
  // the rotation about Z and the translations (they violate G only through the locked joint).
  const double k_scale = maxAbs(lin.problem.stiffness);
  const Eigen::VectorXd rotation = fullorder::rotationRateField(lin.q);
  EXPECT_LT((lin.problem.stiffness * rotation).cwiseAbs().maxCoeff(),
            1e-12 * k_scale * rotation.cwiseAbs().maxCoeff());
  const Eigen::VectorXd shift = model.system().uniformField(Eigen::Vector3d(0.3, -0.2, 0.9));
  EXPECT_LT((lin.problem.stiffness * shift).cwiseAbs().maxCoeff(), 1e-12 * k_scale);
}

TEST(Linearize, GravityEquilibriumCarriesTheWeightThroughTheJoint) {
  fullorder::MastParameters p = fixtures::mastParameters(3);
  const Eigen::Vector3d g(0.0, -9.81, 0.0);
  p.gravity_m_s2 = g;
  const fullorder::MastModel model = buildLockedMast(p, 0.0);
  const Linearization lin = linearizeMast(model);
  ASSERT_TRUE(lin.equilibrium_solved);
  EXPECT_LE(lin.statics.constraint_residual, 1e-12);
  EXPECT_LE(lin.statics.relative_force_residual, 1e-9);

  // Static balance of the whole mast: joint force = −weight; drive torque = −(moment of the weight
  // about Z at the pin) = m g x_c for gravity along −Y with the mast along +X.
  const double mass = model.totalMass();
  EXPECT_LT((model.jointForce(lin.lambda) + mass * g).norm(), 1e-9 * mass * g.norm());
  const Eigen::VectorXd m_q = lin.problem.mass * lin.q;
  const double centroid_x = model.system().uniformField(Eigen::Vector3d::UnitX()).dot(m_q) / mass;
  EXPECT_NEAR(model.driveTorque(lin.lambda), mass * 9.81 * centroid_x,
              1e-9 * mass * 9.81 * centroid_x);
  // The preload makes the multipliers of the rigid and bonded constraints non-zero.
  EXPECT_GT(lin.lambda.cwiseAbs().maxCoeff(), 1.0);
}

TEST(Linearize, MisuseIsAnInputError) {
  const fullorder::MastModel driven = fullorder::buildMast(fixtures::mastParameters(2));
  EXPECT_THROW(linearizeMast(driven), InputError);
  const fullorder::MastModel locked = buildLockedMast(fixtures::mastParameters(2), 0.0);
  EXPECT_THROW(linearize(locked.system(), Eigen::VectorXd::Zero(5)), InputError);
}

/// Lowest modes of the resin mast under gravity g at θ0, with or without the multiplier term.
struct PreloadedModes {
  fullorder::MastModel model;
  Linearization lin;
  ModalAnalysis modes;
};

PreloadedModes preloadedModes(const Eigen::Vector3d& g, double angle_rad, MultiplierTerm term,
                              int count = 6) {
  fullorder::MastParameters p = fixtures::resinMast(2, 1, 6);
  p.gravity_m_s2 = g;
  PreloadedModes out{buildLockedMast(p, angle_rad), {}, {}};
  LinearizationOptions options;
  options.multiplier_term = term;
  out.lin = linearizeMast(out.model, options);
  out.modes = analyzeMast(out.model, out.lin, dense(count));
  EXPECT_TRUE(out.modes.eigen.ok()) << out.modes.eigen.message;
  return out;
}

TEST(MultiplierTerm, FrequencySquaredIsTheCurvatureOfThePotentialOnTheConstraintManifold) {
  // Real gravity along the mast axis (θ0 = 90°: the mast stands along +Y, gravity −Y compresses
  // it). For a mass-normalised mode, ω² = φᵀKφ must equal d²Π/ds² along any curve on Φ = 0 with
  // tangent φ (modes/linearize.hpp). Central differences with a 1e-5 m amplitude are accurate to
  // ~1e-9 (round-off of Π and O(s²) truncation, measured at 1e-6 and 1e-7 too).
  const Eigen::Vector3d g(0.0, -9.81, 0.0);
  double worst_with = 0.0, worst_without = 0.0;
  for (MultiplierTerm term : {MultiplierTerm::Include, MultiplierTerm::Exclude}) {
    const PreloadedModes m = preloadedModes(g, 90.0 * kDeg, term);
    for (int k = 0; k < m.modes.eigen.converged; ++k) {
      const double omega2 = m.modes.eigen.eigenvalues_rad2_s2(k);
      const double curvature =
          fixtures::manifoldCurvature(m.model.system(), m.lin.q, m.modes.eigen.modes.col(k));
      const double error = std::abs(curvature / omega2 - 1.0);
      (term == MultiplierTerm::Include ? worst_with : worst_without) =
          std::max(term == MultiplierTerm::Include ? worst_with : worst_without, error);
    }
  }
  std::printf(
      "[ measured ] |d2Pi/ds2 / omega^2 - 1| over 6 modes: with (Phi_q^T lambda)_q %.2e, "
      "without %.2e\n",
      worst_with, worst_without);
  EXPECT_LT(worst_with, 1e-8);
  EXPECT_GT(worst_without, 1e-6) << "the multiplier term should matter under this preload";
}

TEST(AngleDependence, WithoutGravityFrequenciesDoNotDependOnTheAngle) {
  const fullorder::MastParameters p = fixtures::mastParameters(3);
  const fullorder::MastModel reference_model = buildLockedMast(p, 0.0);
  const ModalAnalysis reference =
      analyzeMast(reference_model, linearizeMast(reference_model), dense(10));
  for (double angle_deg : {30.0, 90.0, 200.0}) {
    const fullorder::MastModel model = buildLockedMast(p, angle_deg * kDeg);
    const Linearization lin = linearizeMast(model);
    const ModalAnalysis a = analyzeMast(model, lin, dense(10));
    ASSERT_EQ(a.eigen.converged, reference.eigen.converged);
    for (int k = 0; k < a.eigen.converged; ++k) {
      EXPECT_NEAR(a.eigen.frequencies_hz(k), reference.eigen.frequencies_hz(k),
                  1e-10 * reference.eigen.frequencies_hz(k))
          << "mode " << k + 1 << " at " << angle_deg << " deg";
      // The shapes rotate rigidly with the mast (canonical bases make even the pairs match).
      const Eigen::VectorXd back = fullorder::rotateEveryBlock(a.eigen.modes.col(k), fullorder::rotationAboutZ(-angle_deg * kDeg));
      const double dot =
          back.dot(reference_model.system().massMatrix() * reference.eigen.modes.col(k));
      EXPECT_NEAR(std::abs(dot), 1.0, 1e-8) << "mode " << k + 1 << " at " << angle_deg << " deg";
    }
  }
}

TEST(AngleDependence, GravityAlongTheJointAxisKeepsFrequenciesIndependentOfTheAngle) {
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const PreloadedModes a = preloadedModes(g, 0.0, MultiplierTerm::Include);
  const PreloadedModes b = preloadedModes(g, 70.0 * kDeg, MultiplierTerm::Include);
  for (int k = 0; k < a.modes.eigen.converged; ++k)
    EXPECT_NEAR(b.modes.eigen.frequencies_hz(k), a.modes.eigen.frequencies_hz(k),
                1e-10 * a.modes.eigen.frequencies_hz(k));
}

TEST(AngleDependence, InPlaneGravityShiftWithAngleIsPredictedOnlyWithTheMultiplierTerm) {
  // Real in-plane gravity −Y: horizontal (θ0 = 0, bending load) versus vertical (θ0 = 90°, axial
  // compression). Reference for the shift of ω² of each mode: the manifold curvature of Π along the
  // full linearisation's modes at both angles (an exact eigenpair's Rayleigh quotient equals its
  // eigenvalue).
  const Eigen::Vector3d g(0.0, -9.81, 0.0);
  const PreloadedModes h_with = preloadedModes(g, 0.0, MultiplierTerm::Include);
  const PreloadedModes v_with = preloadedModes(g, 90.0 * kDeg, MultiplierTerm::Include);
  const PreloadedModes h_without = preloadedModes(g, 0.0, MultiplierTerm::Exclude);
  const PreloadedModes v_without = preloadedModes(g, 90.0 * kDeg, MultiplierTerm::Exclude);
  const int k = 0;  // first bending mode (in-plane at θ0 = 0: bending-y)
  ASSERT_EQ(h_with.modes.labels[k], "bending-y");
  const double reference = fixtures::manifoldCurvature(v_with.model.system(), v_with.lin.q,
                                                       v_with.modes.eigen.modes.col(k)) -
                           fixtures::manifoldCurvature(h_with.model.system(), h_with.lin.q,
                                                       h_with.modes.eigen.modes.col(k));
  const double with =
      v_with.modes.eigen.eigenvalues_rad2_s2(k) - h_with.modes.eigen.eigenvalues_rad2_s2(k);
  const double without =
      v_without.modes.eigen.eigenvalues_rad2_s2(k) - h_without.modes.eigen.eigenvalues_rad2_s2(k);
  const double f0 = h_with.modes.eigen.frequencies_hz(k);
  std::printf(
      "[ measured ] first bending %.6f Hz at 0 deg; f(90 deg)/f(0 deg) - 1 = %.3e with the "
      "multiplier term, %.3e without; shift of omega^2: reference %.6e, with %.6e, without "
      "%.6e rad^2/s^2\n",
      f0, v_with.modes.eigen.frequencies_hz(k) / f0 - 1.0,
      v_without.modes.eigen.frequencies_hz(k) / h_without.modes.eigen.frequencies_hz(k) - 1.0,
      reference, with, without);
  // The angle matters far above the solver's round-off (~1e-12 relative) …
  EXPECT_GT(std::abs(with), 1e-6 * h_with.modes.eigen.eigenvalues_rad2_s2(k));
  // … the full tangent predicts the shift, the tangent without the multiplier term does not.
  EXPECT_LT(std::abs(with - reference), 1e-2 * std::abs(reference));
  EXPECT_GT(std::abs(without - reference), 5e-2 * std::abs(reference));
}

}  // namespace
}  // namespace mastrom::modes
