// Rigid-rotation symmetry of the mast (DaeSystem::rotationSymmetry): the declared row and
// coordinate triples must make the iteration matrix exactly equivariant,
//     H(R_δ q, R_δ q̇, P_δ λ, t′) = P_δ H(q, q̇, λ, t) P_δᵀ,   δ = θ(t′) − θ(t),
// for the assembled and for the eliminated system; a fixed frame must switch the symmetry off; and
// generalized-α must give the same deployment with and without reusing factorisations across turns.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "assembly_test_helpers.hpp"
#include "coarse_mast.hpp"
#include "tests/support/clamped_cylinder.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {
namespace {

Eigen::Matrix3d turnAboutZ(double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

/// P_δ as a dense matrix (its action on the unit vectors).
Eigen::MatrixXd denseTurn(const RotationSymmetry& symmetry, int size, double delta_rad) {
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(size, size);
  for (int j = 0; j < size; ++j) {
    Eigen::VectorXd column = p.col(j);
    symmetry.rotate(delta_rad, column);
    p.col(j) = column;
  }
  return p;
}

/// Coefficients that weight every block of H comparably for a 1e-4 s step (mass, damping and
/// stiffness terms all enter; σ = 1).
IterationCoefficients newtonLike() { return IterationCoefficients{1.0, 5e-5, 3e-9, 1.0}; }

struct TurnedStates {
  Eigen::VectorXd q1, qdot1, lambda1, q2, qdot2, lambda2;
  double t1 = 0.0, t2 = 0.0, delta_rad = 0.0;
};

/// A deformed, moving state at t1 and the same state turned to the drive angle of t2.
TurnedStates turnedStates(const MastModel& mast, const MultibodySystem& sys) {
  const int n = sys.dofCount(), m = sys.constraintCount();
  TurnedStates s;
  s.t1 = 0.35;
  s.t2 = 2.8;
  const double theta1 = mast.baseJoint().driveAt(s.t1).angle_rad;
  s.delta_rad = mast.baseJoint().driveAt(s.t2).angle_rad - theta1;
  std::mt19937 gen(2026);
  // 0.1 mm deformations: strains ~2e-3, far beyond a deployment's, so the check is not trivial.
  s.q1 = mast.rotatedReference(theta1) + testing::randomVector(gen, n, 1e-4);
  s.qdot1 = testing::randomVector(gen, n, 0.1);
  s.lambda1 = testing::randomVector(gen, m, 10.0);
  const Eigen::Matrix3d r = turnAboutZ(s.delta_rad);
  s.q2 = sys.rotated(s.q1, r);
  s.qdot2 = sys.rotated(s.qdot1, r);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n + m);
  x.tail(m) = s.lambda1;
  sys.rotationSymmetry()->rotate(s.delta_rad, x);
  s.lambda2 = x.tail(m);
  return s;
}

TEST(RotationSymmetry, AssembledMastIterationMatrixAndConstraintsAreEquivariant) {
  MastParameters p;
  p.modules = 3;
  p.damping_s = 1e-5;
  const MastModel mast = buildMast(p);
  const MultibodySystem& sys = mast.system();
  const RotationSymmetry* symmetry = sys.rotationSymmetry();
  ASSERT_NE(symmetry, nullptr);
  const int n = sys.dofCount(), m = sys.constraintCount();
  // Every coordinate block, plus the joint's pin rows and two vector rows per bonded node.
  const int bonded_nodes = 2 * (p.modules - 1) * p.elements_circumferential;
  EXPECT_EQ(static_cast<int>(symmetry->triple_starts.size()), n / 3 + 1 + 2 * bonded_nodes);
  EXPECT_GT(mast.baseJoint().driveAt(2.8).angle_rad, 0.5);  // a real turn, not a few degrees

  const TurnedStates s = turnedStates(mast, sys);
  SparseMatrix h1, h2;
  sys.assembleIterationMatrix(s.q1, s.qdot1, s.lambda1, s.t1, newtonLike(), h1);
  sys.assembleIterationMatrix(s.q2, s.qdot2, s.lambda2, s.t2, newtonLike(), h2);
  const Eigen::MatrixXd p_turn = denseTurn(*symmetry, n + m, s.delta_rad);
  const Eigen::MatrixXd expected = p_turn * Eigen::MatrixXd(h1) * p_turn.transpose();
  // Same sums in a turned frame: round-off of the largest entries (stiffness × 3e-9 ≈ mass) only.
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_LT((Eigen::MatrixXd(h2) - expected).cwiseAbs().maxCoeff(), 1e-12 * scale);

  // Φ(R q, t′) = P Φ(q, t): the bonded and module rows, the pin and the drive row (time shift).
  Eigen::VectorXd phi1, phi2;
  sys.constraints(s.q1, s.t1, phi1);
  sys.constraints(s.q2, s.t2, phi2);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n + m);
  x.tail(m) = phi1;
  symmetry->rotate(s.delta_rad, x);
  EXPECT_LT((phi2 - x.tail(m)).cwiseAbs().maxCoeff(), 1e-13 * (1.0 + phi1.cwiseAbs().maxCoeff()));
  EXPECT_GT(phi1.cwiseAbs().maxCoeff(), 1e-6);  // the state really violates them
}

TEST(RotationSymmetry, EliminatedSystemInheritsItAndStaysEquivariant) {
  MastParameters p;
  p.modules = 3;
  p.damping_s = 1e-5;
  MastModel mast = buildMast(p);
  MultibodySystem& sys = mast.system();
  EliminatedSystem reduced(sys);
  const RotationSymmetry* symmetry = reduced.rotationSymmetry();
  ASSERT_NE(symmetry, nullptr);
  const int nr = reduced.dofCount(), mr = reduced.constraintCount();
  const TurnedStates full = turnedStates(mast, sys);
  const Eigen::VectorXd q1 = reduced.restrict(full.q1), q2 = reduced.restrict(full.q2);
  const Eigen::VectorXd v1 = reduced.restrict(full.qdot1), v2 = reduced.restrict(full.qdot2);
  Eigen::VectorXd l1(mr), l2(mr);
  for (int i = 0; i < mr; ++i) {
    l1[i] = full.lambda1[reduced.keptRows()[static_cast<std::size_t>(i)]];
    l2[i] = full.lambda2[reduced.keptRows()[static_cast<std::size_t>(i)]];
  }
  EXPECT_DOUBLE_EQ(reduced.rotationAngle(full.t2) - reduced.rotationAngle(full.t1), full.delta_rad);
  SparseMatrix h1, h2;
  reduced.iterationMatrix(q1, v1, l1, full.t1, newtonLike(), h1);
  reduced.iterationMatrix(q2, v2, l2, full.t2, newtonLike(), h2);
  const Eigen::MatrixXd p_turn = denseTurn(*symmetry, nr + mr, full.delta_rad);
  const Eigen::MatrixXd expected = p_turn * Eigen::MatrixXd(h1) * p_turn.transpose();
  EXPECT_LT((Eigen::MatrixXd(h2) - expected).cwiseAbs().maxCoeff(),
            1e-12 * expected.cwiseAbs().maxCoeff());
}

TEST(RotationSymmetry, AFixedFrameBreaksIt) {
  ClampedCylinderParameters p;
  ClampedShell shell = buildClampedCylinder(p);  // nodes bonded to the ground
  EXPECT_EQ(shell.system.rotationSymmetry(), nullptr);
  EliminatedSystem reduced(shell.system);
  EXPECT_EQ(reduced.rotationSymmetry(), nullptr);
}

// Reusing a factorisation across turns changes only how Newton and the index-1 recovery converge:
// both runs solve the same discrete equations to the same tolerances (force criterion 1e-6), so
// their outputs agree to that level, while the turned reuse needs fewer iterations.
TEST(RotationSymmetry, ReuseAcrossTurnsGivesTheSameDeploymentWithFewerIterations) {
  Config c = testing::coarseScheme1();
  c.drive.angle_deg = 30.0;
  c.drive.duration_s = 0.06;
  c.drive.ramp_s = 0.015;
  MastModel model = buildMast(mastParametersFromConfig(c));
  DeploymentOptions o;
  o.integrator = integratorFromConfig(c);
  o.end_time_s = 0.07;
  DeploymentStatistics turned, plain;
  o.integrator.reuse_across_rotation = true;
  const DeploymentSeries a = simulateDeployment(model, o, &turned);
  o.integrator.reuse_across_rotation = false;
  const DeploymentSeries b = simulateDeployment(model, o, &plain);
  ASSERT_EQ(a.size(), b.size());
  double peak_rel = 0, peak_tau = 0, peak_f = 0, d_rel = 0, d_tau = 0, d_f = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    peak_rel = std::max(peak_rel, std::abs(b.end_relative_angular_acceleration_rad_s2[i]));
    peak_tau = std::max(peak_tau, std::abs(b.joint_torque_nm[i]));
    peak_f = std::max(peak_f, b.joint_force_n[i].norm());
    d_rel = std::max(d_rel, std::abs(a.end_relative_angular_acceleration_rad_s2[i] -
                                     b.end_relative_angular_acceleration_rad_s2[i]));
    d_tau = std::max(d_tau, std::abs(a.joint_torque_nm[i] - b.joint_torque_nm[i]));
    d_f = std::max(d_f, (a.joint_force_n[i] - b.joint_force_n[i]).norm());
  }
  std::printf(
      "[ measured ] turned vs plain reuse: Newton it/step %.3f vs %.3f, factorisations %ld "
      "vs %ld; max diff / peak: rel. acceleration %.2e, torque %.2e, force %.2e\n",
      double(turned.newton_iterations) / double(turned.steps),
      double(plain.newton_iterations) / double(plain.steps), turned.factorizations,
      plain.factorizations, d_rel / peak_rel, d_tau / peak_tau, d_f / peak_f);
  EXPECT_LT(d_rel, 1e-4 * peak_rel);
  EXPECT_LT(d_tau, 1e-4 * peak_tau);
  EXPECT_LT(d_f, 1e-4 * peak_f);
  EXPECT_LT(turned.newton_iterations, plain.newton_iterations);
  EXPECT_LE(turned.factorizations, plain.factorizations);
}

}  // namespace
}  // namespace mastrom::fullorder
