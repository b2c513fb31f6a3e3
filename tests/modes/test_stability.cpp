// The stability check of a linearisation point (modes/stability.hpp): the count of negative
// eigenvalues of the constrained tangent from the inertia of the saddle matrix, against the
// eigenvalues themselves — of a 4 × 4 problem written down by hand, and of a mast whose full
// spectrum the dense solver computes independently.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <string>

#include "common/error.hpp"
#include "modes/linearize.hpp"
#include "modes/stability.hpp"
#include "tests/modes/mast_fixtures.hpp"

namespace mastrom::modes {
namespace {

/// K = diag(k), M = I, G = the unit row of `constrained`: the constrained eigenvalues are the
/// entries of k other than k[constrained].
ConstrainedEigenproblem diagonalProblem(const Eigen::Vector4d& k, int constrained) {
  ConstrainedEigenproblem p;
  p.stiffness.resize(4, 4);
  p.mass.resize(4, 4);
  for (int i = 0; i < 4; ++i) {
    p.stiffness.insert(i, i) = k(i);
    p.mass.insert(i, i) = 1.0;
  }
  p.constraint_jacobian.resize(1, 4);
  p.constraint_jacobian.insert(0, constrained) = 1.0;
  p.stiffness.makeCompressed();
  p.mass.makeCompressed();
  p.constraint_jacobian.makeCompressed();
  return p;
}

TEST(Stability, InertiaCountsConstrainedEigenvaluesBelowTheShift) {
  // Constrained eigenvalues {1, −2, 4}: the constraint removes the 3.
  const ConstrainedEigenproblem p = diagonalProblem(Eigen::Vector4d(1.0, -2.0, 3.0, 4.0), 2);
  EXPECT_EQ(constrainedInertia(p, 0.0).below, 1);
  EXPECT_EQ(constrainedInertia(p, -3.0).below, 0);
  EXPECT_EQ(constrainedInertia(p, 2.5).below, 2);  // 3 is constrained away: not counted
  EXPECT_EQ(constrainedInertia(p, 5.0).below, 3);
  // A shift at an eigenvalue is a zero pivot.
  EXPECT_EQ(constrainedInertia(p, 1.0).at, 1);
}

TEST(Stability, NegativeStiffnessRemovedByTheConstraintIsStable) {
  const StabilityReport r =
      checkStability(diagonalProblem(Eigen::Vector4d(1.0, -2.0, 3.0, 4.0), 1));
  EXPECT_TRUE(r.checked);
  EXPECT_TRUE(r.stable());
  EXPECT_EQ(r.negative, 0);
}

TEST(Stability, LowestEigenpairOfAnUnstableProblem) {
  const StabilityReport r =
      checkStability(diagonalProblem(Eigen::Vector4d(1.0, -2.0, 3.0, 4.0), 2));
  EXPECT_FALSE(r.stable());
  EXPECT_EQ(r.negative, 1);
  EXPECT_NEAR(r.lowest_omega2, -2.0, 1e-12);
  ASSERT_EQ(r.lowest_shape.size(), 4);
  EXPECT_NEAR(std::abs(r.lowest_shape(1)), 1.0, 1e-12);  // the unit vector e₂, M-normalised
  EXPECT_NEAR(r.lowest_shape.norm(), 1.0, 1e-12);
}

/// Scheme 3 made soft and heavy (resin-like modulus 0.25 GPa, 0.5 mm walls, 5 kg modules) with
/// gravity across the mast: the preload buckles the shells.
fullorder::MastParameters softHeavyMast() {
  Config c;  // through the configuration, so the modules' inertia follows their mass
  c.mast.modules = 4;
  c.material.youngs_modulus_pa = 2.5e8;
  c.interface.thickness_m = 0.0005;
  c.module.mass_kg = 5.0;
  c.simulation.gravity_m_s2 = {0.0, -9.81, 0.0};
  return fullorder::mastParametersFromConfig(c);
}

TEST(Stability, DefaultMastIsStable) {
  const fullorder::MastModel model = buildLockedMast(fixtures::mastParameters(2), 0.3);
  const Linearization lin = linearizeMast(model);
  EXPECT_TRUE(lin.stability.checked);
  EXPECT_TRUE(lin.stability.stable());
  EXPECT_EQ(lin.stability.neutral, 0);
}

TEST(Stability, SoftHeavyMastUnderGravityAppliedAtOnceIsUnstableAndRefused) {
  const fullorder::MastModel model = buildLockedMast(softHeavyMast(), 0.5 * fixtures::kDeg);
  LinearizationOptions at_once;  // all of gravity in one Newton solve, no continuation
  at_once.stability = StabilityPolicy::Record;
  at_once.continue_load = false;
  const Linearization lin = linearizeMast(model, at_once);
  ASSERT_FALSE(lin.stability.stable());

  // Independent reference: every eigenvalue of the constrained pencil from the dense solver.
  EigenSolverOptions all;
  all.backend = EigenBackendKind::Dense;
  all.count = static_cast<int>(lin.problem.dofs() - lin.problem.constraints());
  const EigenResult spectrum = solveConstrainedEigenproblem(lin.problem, all);
  ASSERT_TRUE(spectrum.ok());
  int negative = 0;
  for (Eigen::Index i = 0; i < spectrum.eigenvalues_rad2_s2.size(); ++i)
    negative += spectrum.eigenvalues_rad2_s2(i) < 0.0;
  EXPECT_EQ(lin.stability.negative, negative);
  const double lowest = spectrum.eigenvalues_rad2_s2.minCoeff();
  EXPECT_NEAR(lin.stability.lowest_omega2, lowest, 1e-8 * std::abs(lowest));
  // The value the dense spectrum gave when the problem was found: −650.78 Hz, a shell mode.
  EXPECT_NEAR(lin.stability.lowestFrequencyHz(), -650.78, 0.01);
  EXPECT_EQ(lin.stability.lowest_label, "shell n=3");

  LinearizationOptions refuse = at_once;
  refuse.stability = StabilityPolicy::Refuse;
  try {
    (void)linearizeMast(model, refuse);
    FAIL() << "an unstable equilibrium was not refused";
  } catch (const NumericalError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("unstable"), std::string::npos) << message;
    EXPECT_NE(message.find("shell n=3"), std::string::npos) << message;
    EXPECT_NE(message.find("--allow-unstable"), std::string::npos) << message;
  }
}

TEST(Stability, LoadContinuationReachesTheStableBranchTheFullOrderSettlesOn) {
  // The default: gravity applied in increments from the reference. The nonlinear full order swung
  // to 0.5° settles on a state with 0.0350 m end deflection that rings at 2.7476 Hz (measured with
  // `mastrom simulate`); the one-step equilibrium has 0.0316 m and f1 = 3.0873 Hz.
  const fullorder::MastModel model = buildLockedMast(softHeavyMast(), 0.5 * fixtures::kDeg);
  const Linearization lin = linearizeMast(model);
  ASSERT_TRUE(lin.stability.stable());
  EXPECT_NE(lin.stability.branch.find("increments"), std::string::npos) << lin.stability.branch;
  EXPECT_NE(lin.stability.branch.find("shell n=3"), std::string::npos) << lin.stability.branch;
  EigenSolverOptions lowest;
  lowest.backend = EigenBackendKind::Dense;
  lowest.count = 1;
  const EigenResult first = solveConstrainedEigenproblem(lin.problem, lowest);
  ASSERT_TRUE(first.ok());
  EXPECT_NEAR(first.frequencies_hz(0), 2.7476, 1e-3 * 2.7476);  // within 0.1 %
}

}  // namespace
}  // namespace mastrom::modes
