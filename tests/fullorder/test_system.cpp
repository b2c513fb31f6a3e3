// Multibody system assembly (fullorder/multibody_system.hpp) on a mast: invariance of the forces
// under rigid motion, the iteration matrix against finite differences of forces and constraints,
// the fixed sparsity pattern, and the kinetic energy of a rigid rotation against an independent
// moment of inertia.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>

#include "assembly_test_helpers.hpp"
#include "common/error.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kPi = 3.14159265358979323846;

MastParameters scheme(int modules, double damping_s = 0.0) {
  MastParameters p;
  p.modules = modules;
  p.damping_s = damping_s;
  return p;
}

/// A rigid velocity: ω × (every 3-block) plus v on position blocks.
Eigen::VectorXd rigidVelocity(const MultibodySystem& sys, const Eigen::VectorXd& q,
                              const Eigen::Vector3d& omega, const Eigen::Vector3d& v) {
  Eigen::VectorXd qdot(q.size());
  for (Eigen::Index k = 0; k < q.size() / 3; ++k)
    qdot.segment<3>(3 * k) = omega.cross(Eigen::Vector3d(q.segment<3>(3 * k)));
  return qdot + sys.uniformField(v);
}

/// Dense (Φ_qᵀλ − f)(q, q̇): the first block row of the static/dynamic residual.
Eigen::VectorXd residual(const MultibodySystem& sys, const Eigen::VectorXd& q,
                         const Eigen::VectorXd& qdot, const Eigen::VectorXd& lambda, double t) {
  Eigen::VectorXd f;
  sys.forces(q, qdot, t, f);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(q.size());
  sys.addConstraintForces(q, lambda, t, r);
  return r - f;
}

TEST(MultibodySystem, ElasticAndDampingForcesVanishUnderRigidMotion) {
  const MastModel mast = buildMast(scheme(3, 1e-5));
  const MultibodySystem& sys = mast.system();
  const Eigen::VectorXd q0 = sys.referenceCoordinates();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(sys.dofCount());
  Eigen::VectorXd f;
  sys.forces(q0, zero, 0.0, f);
  // Exactly stress-free reference (strains measured against the interpolated e₀).
  EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(sys.strainEnergy(q0), 1e-20);

  // Force scale for the tolerance: a 1 µm random deformation gives forces ~ K·1e-6.
  std::mt19937 gen(31);
  const Eigen::VectorXd small = q0 + testing::randomVector(gen, sys.dofCount(), 1e-6);
  Eigen::VectorXd f_small;
  sys.forces(small, zero, 0.0, f_small);
  const double scale = f_small.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 1.0);

  const Eigen::Matrix3d rot = testing::randomRotationMatrix(gen);
  const Eigen::Vector3d shift(0.3, -1.2, 0.4);
  const Eigen::VectorXd q = sys.rotated(q0, rot) + sys.uniformField(shift);
  const Eigen::VectorXd qdot =
      rigidVelocity(sys, q, Eigen::Vector3d(0.3, -2.0, 1.1), Eigen::Vector3d(1, 2, 3));
  sys.forces(q, qdot, 0.0, f);
  // Round-off of strains ~1e-16 against the 1e-6/a ≈ 4e-5 strains of the scale state: ratio ≲
  // 1e-10.
  EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT(sys.strainEnergy(q), 1e-20);
  EXPECT_LT(sys.dampingPower(q, qdot), 1e-20);
  // The bonded edges and module constraints are invariant too (the base joint is not).
  Eigen::VectorXd phi;
  sys.constraints(q, 0.0, phi);
  for (int k = 0; k < sys.constraintBlockCount(); ++k) {
    const int off = sys.constraintBlockOffset(k);
    if (off == mast.jointMultiplierOffset()) continue;
    EXPECT_LT(phi.segment(off, sys.constraintBlock(k).size()).cwiseAbs().maxCoeff(), 1e-14)
        << sys.constraintBlock(k).name();
  }
}

TEST(MultibodySystem, IterationMatrixAgreesWithFiniteDifferences) {
  MastParameters p = scheme(2, 1e-3);  // large μ so that C_t and K_d are well exercised
  p.drive.kind = DriveLawKind::Cycloidal;
  p.drive.duration_s = 2.0;
  const MastModel mast = buildMast(p);
  const MultibodySystem& sys = mast.system();
  const int n = sys.dofCount(), m = sys.constraintCount();
  std::mt19937 gen(32);
  const double t = 0.6;
  const Eigen::VectorXd q = mast.rotatedReference(0.4) + testing::randomVector(gen, n, 1e-3);
  const Eigen::VectorXd qdot = testing::randomVector(gen, n, 0.1);
  const Eigen::VectorXd lambda = testing::randomVector(gen, m, 10.0);

  SparseMatrix h;
  IterationCoefficients k_only;
  k_only.mass = 0.0;
  k_only.damping = 0.0;
  k_only.stiffness = 1.0;
  k_only.constraint_scale = 1.0;
  sys.assembleIterationMatrix(q, qdot, lambda, t, k_only, h);
  const Eigen::MatrixXd hd = Eigen::MatrixXd(h);
  ASSERT_EQ(hd.rows(), n + m);

  // K block: ∂(Φ_qᵀλ − f)/∂q with f containing elastic, damping (K_d) terms. Step ∛ε·0.1 m:
  // truncation ~(h/a)² ≈ 1e-9 and round-off ε|F|/h ≈ 1e-13 relative to max|K|.
  const Eigen::MatrixXd k_fd = testing::centralJacobian(
      [&](const Eigen::VectorXd& x) { return residual(sys, x, qdot, lambda, t); }, q, 0.1);
  const double k_scale = k_fd.cwiseAbs().maxCoeff();
  EXPECT_LT((hd.topLeftCorner(n, n) - k_fd).cwiseAbs().maxCoeff(), 1e-7 * k_scale);

  // Constraint blocks: Φ_q against differences of Φ, and the transpose above the diagonal.
  auto phi_of = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd phi;
    sys.constraints(x, t, phi);
    return phi;
  };
  const Eigen::MatrixXd g_fd = testing::centralJacobian(phi_of, q, 0.1);
  EXPECT_LT((hd.bottomLeftCorner(m, n) - g_fd).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT((hd.topRightCorner(n, m) - g_fd.transpose()).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_EQ(hd.bottomRightCorner(m, m).cwiseAbs().maxCoeff(), 0.0);
  SparseMatrix g;
  sys.constraintJacobian(q, t, g);
  EXPECT_LT((Eigen::MatrixXd(g) - g_fd).cwiseAbs().maxCoeff(), 1e-8);

  // C block (c_d = 1 only): ∂(−f)/∂q̇ = C_t, differences in q̇ (F_d linear in q̇: exact up to
  // round-off).
  IterationCoefficients c_only = k_only;
  c_only.stiffness = 0.0;
  c_only.damping = 1.0;
  c_only.constraint_scale = 2.5;
  sys.assembleIterationMatrix(q, qdot, lambda, t, c_only, h);
  const Eigen::MatrixXd hc = Eigen::MatrixXd(h);
  const Eigen::MatrixXd c_fd = testing::centralJacobian(
      [&](const Eigen::VectorXd& v) { return residual(sys, q, v, lambda, t); }, qdot, 0.1);
  EXPECT_LT((hc.topLeftCorner(n, n) - c_fd).cwiseAbs().maxCoeff(),
            1e-7 * c_fd.cwiseAbs().maxCoeff());
  EXPECT_GT(c_fd.cwiseAbs().maxCoeff(), 1e-3 * k_scale * 1e-3);  // damping is really present
  // The constraint scale multiplies both off-diagonal blocks.
  EXPECT_LT((hc.bottomLeftCorner(m, n) - 2.5 * g_fd).cwiseAbs().maxCoeff(), 3e-8);

  // M block (c_m = 1 only) is the mass matrix.
  IterationCoefficients m_only = k_only;
  m_only.stiffness = 0.0;
  m_only.mass = 1.0;
  sys.assembleIterationMatrix(q, qdot, lambda, t, m_only, h);
  EXPECT_EQ((Eigen::MatrixXd(h).topLeftCorner(n, n) - Eigen::MatrixXd(sys.massMatrix()))
                .cwiseAbs()
                .maxCoeff(),
            0.0);

  // Combined call: forces identical to forces(), matrix identical to the separate call.
  IterationCoefficients all;
  all.mass = 1e4;
  all.damping = 1e2;
  all.stiffness = 1.0;
  all.constraint_scale = 1e6;
  SparseMatrix h1, h2;
  Eigen::VectorXd f1, f2;
  sys.assembleIterationMatrix(q, qdot, lambda, t, all, h1);
  sys.assembleForcesAndIterationMatrix(q, qdot, lambda, t, all, f2, h2);
  sys.forces(q, qdot, t, f1);
  EXPECT_EQ((Eigen::MatrixXd(h1) - Eigen::MatrixXd(h2)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT((f1 - f2).cwiseAbs().maxCoeff(), 1e-12 * f1.cwiseAbs().maxCoeff());
}

TEST(MultibodySystem, PatternIsBuiltOnceAndReused) {
  const MastModel mast = buildMast(scheme(2));
  const MultibodySystem& sys = mast.system();
  const int n = sys.dofCount(), m = sys.constraintCount();
  const Eigen::VectorXd q = sys.referenceCoordinates();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd lambda = Eigen::VectorXd::Ones(m);
  SparseMatrix h;
  IterationCoefficients c;
  sys.assembleIterationMatrix(q, zero, lambda, 0.0, c, h);
  EXPECT_EQ(h.nonZeros(), sys.iterationMatrixPattern().nonZeros());
  const double* values = h.valuePtr();
  const int* inner = h.innerIndexPtr();
  sys.assembleIterationMatrix(q, zero, lambda, 0.0, c, h);
  EXPECT_EQ(h.valuePtr(), values);  // no reallocation: values scattered in place
  EXPECT_EQ(h.innerIndexPtr(), inner);
  // The pattern holds the whole diagonal (for shifts) and is structurally symmetric.
  const Eigen::MatrixXd pattern = Eigen::MatrixXd(sys.iterationMatrixPattern());
  SparseMatrix ones = sys.iterationMatrixPattern();
  ones.coeffs().setOnes();
  const Eigen::MatrixXd dense_ones = Eigen::MatrixXd(ones);
  EXPECT_EQ(dense_ones.diagonal().minCoeff(), 1.0);
  EXPECT_EQ((dense_ones - dense_ones.transpose()).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(pattern.cwiseAbs().maxCoeff(), 0.0);
}

TEST(MultibodySystem, DaeInterfaceAndTimeDerivatives) {
  MastParameters p = scheme(2);
  p.drive.kind = DriveLawKind::Quintic;
  p.drive.duration_s = 2.0;
  MastModel mast = buildMast(p);
  MultibodySystem& sys = mast.system();
  const double t = 0.8;
  const DriveState ds = mast.baseJoint().driveAt(t);
  // The rigid rotation θ(t) of the stowed mast satisfies every constraint.
  Eigen::VectorXd q = mast.rotatedReference(ds.angle_rad);
  Eigen::VectorXd phi;
  sys.constraints(q, t, phi);
  EXPECT_LT(phi.cwiseAbs().maxCoeff(), 1e-15);
  // With the rigid velocity θ̇ Z × q the velocity constraint Φ_q q̇ = −Φ_t holds.
  const Eigen::VectorXd qdot =
      rigidVelocity(sys, q, Eigen::Vector3d(0, 0, ds.rate_rad_s), Eigen::Vector3d::Zero());
  SparseMatrix g;
  sys.constraintJacobian(q, t, g);
  Eigen::VectorXd rhs;
  sys.velocityConstraintRhs(q, t, rhs);
  EXPECT_LT((g * qdot - rhs).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_GT(rhs.cwiseAbs().maxCoeff(), 0.1);
  // And the rigid acceleration θ̈ Z × q + θ̇² Z × (Z × q) satisfies Φ_q q̈ = rhs of the acceleration
  // rows.
  Eigen::VectorXd qddot(q.size());
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  for (Eigen::Index k = 0; k < q.size() / 3; ++k) {
    const Eigen::Vector3d b = q.segment<3>(3 * k);
    qddot.segment<3>(3 * k) =
        ds.acceleration_rad_s2 * z.cross(b) + ds.rate_rad_s * ds.rate_rad_s * z.cross(z.cross(b));
  }
  sys.accelerationConstraintRhs(q, qdot, t, rhs);
  EXPECT_LT((g * qddot - rhs).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(MultibodySystem, KineticEnergyOfARigidRotationMatchesTheMomentOfInertia) {
  for (int modules : {2, 4}) {
    const MastParameters p = scheme(modules);
    const MastModel mast = buildMast(p);
    const MultibodySystem& sys = mast.system();
    const double omega = 1.3;
    const Eigen::VectorXd q = mast.rotatedReference(0.7);
    const Eigen::VectorXd qdot =
        rigidVelocity(sys, q, Eigen::Vector3d(0, 0, omega), Eigen::Vector3d::Zero());

    // Independent J_Z about the joint axis: cubes I_zz = m d²/6 plus m x_k², thin-walled tubes
    // m_t (R²/2 + L²/12) about their centre (transverse axis) plus m_t x_c², m_t = ρ h 2πR L.
    const double d = p.module_side_m, L = p.interface_length_m, R = p.interface_radius_m;
    const double pitch = d + L;
    double jz = 0.0, shell_jz = 0.0;
    for (int k = 0; k < modules; ++k)
      jz += p.module_mass_kg * (d * d / 6.0 + (k * pitch) * (k * pitch));
    const double mt = p.density_kg_m3 * p.interface_thickness_m * 2.0 * kPi * R * L;
    for (int k = 0; k + 1 < modules; ++k) {
      const double xc = k * pitch + 0.5 * d + 0.5 * L;
      shell_jz += mt * (R * R / 2.0 + L * L / 12.0 + xc * xc);
    }
    jz += shell_jz;
    const double ke = sys.kineticEnergy(qdot);
    const double rel = ke / (0.5 * jz * omega * omega) - 1.0;
    // The interpolated ring (8 Hermite arcs) has 5.2e-4 less area than the circle (mesh test), and
    // the shells carry shell_jz/jz ≈ 9–12 % of J_Z: expected deviation ≈ −5e-5. Tolerance 1e-4.
    EXPECT_LT(std::abs(rel), 1e-4) << "modules = " << modules << ", relative error " << rel
                                   << ", shell share " << shell_jz / jz;
    std::cout << "[ kinetic energy ] modules = " << modules
              << ": relative error vs ½J_Zω² = " << rel << " (shell share of J_Z " << shell_jz / jz
              << ")\n";

    // Total mass: modules plus ρh × (reference areas of the elements), exactly.
    double area = 0.0;
    for (int e = 0; e < sys.elementCount(); ++e) area += sys.element(e).referenceArea();
    EXPECT_NEAR(sys.totalMass(),
                modules * p.module_mass_kg + p.density_kg_m3 * p.interface_thickness_m * area,
                1e-13);
  }
}

TEST(MultibodySystem, GravityForceAndPotential) {
  MastParameters p = scheme(3);
  p.gravity_m_s2 = Eigen::Vector3d(0.0, -9.81, 0.0);
  const MastModel mast = buildMast(p);
  const MultibodySystem& sys = mast.system();
  const Eigen::VectorXd q = sys.referenceCoordinates();
  // Resultant of Q_g (virtual work on a unit translation) = total mass × g.
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(sys.gravityForce().dot(sys.uniformField(Eigen::Vector3d::Unit(k))),
                sys.totalMass() * p.gravity_m_s2[k], 1e-13);
  // V_g changes by −m g·δ under a translation δ.
  const Eigen::Vector3d delta(0.01, 0.02, -0.03);
  EXPECT_NEAR(sys.gravityPotential(q + sys.uniformField(delta)) - sys.gravityPotential(q),
              -sys.totalMass() * p.gravity_m_s2.dot(delta), 1e-14);
  // Moment of gravity about Z at the origin = Σ (r × m g)_z: modules at x_k, shells at their
  // centres.
  Eigen::VectorXd rot_mode(q.size());
  for (Eigen::Index k = 0; k < q.size() / 3; ++k)
    rot_mode.segment<3>(3 * k) =
        Eigen::Vector3d::UnitZ().cross(Eigen::Vector3d(q.segment<3>(3 * k)));
  const double shell_mass = (sys.totalMass() - 3 * p.module_mass_kg) / 2;
  const double pitch = p.module_side_m + p.interface_length_m;
  const double expected =
      -9.81 *
      (p.module_mass_kg * (0 + pitch + 2 * pitch) +
       shell_mass * (0.5 * p.module_side_m + 0.5 * p.interface_length_m) * 2 + shell_mass * pitch);
  EXPECT_NEAR(sys.gravityForce().dot(rot_mode), expected, 1e-12);
}

// The eliminated system's per-iteration calls avoid sparse products (precomputed term lists, work
// vectors); the references here are the defining products G_r = S G T and Q_r = Tᵀ Q(T q_r + d)
// formed with Eigen's sparse algebra. Both sum the same few products (≤ 4 terms per entry) in a
// different order, so they agree to a few ulps of the largest term: 1e-14 relative.
TEST(EliminatedSystem, JacobianAndForcesEqualTheDefiningProducts) {
  MastModel mast = buildMast(scheme(3, 1e-5));
  MultibodySystem& sys = mast.system();
  EliminatedSystem reduced(sys);
  std::mt19937 gen(41);
  const Eigen::VectorXd q_r = reduced.restrict(sys.referenceCoordinates()) +
                              testing::randomVector(gen, reduced.dofCount(), 1e-3);
  const Eigen::VectorXd v_r = testing::randomVector(gen, reduced.dofCount(), 1e-1);
  const Eigen::VectorXd q = reduced.expandPositions(q_r), v = reduced.expandRates(v_r);
  const SparseMatrix& t = reduced.transformation();
  SparseMatrix select(reduced.constraintCount(), sys.constraintCount());
  for (std::size_t i = 0; i < reduced.keptRows().size(); ++i)
    select.insert(static_cast<Eigen::Index>(i), reduced.keptRows()[i]) = 1.0;
  SparseMatrix g, g_r;
  for (int call = 0; call < 2; ++call) {  // the second call reuses the stored pattern
    sys.constraintJacobian(q, 0.1, g);
    reduced.constraintJacobian(q_r, 0.1, g_r);
    const Eigen::MatrixXd expected = Eigen::MatrixXd(select * g * t);
    EXPECT_LT((Eigen::MatrixXd(g_r) - expected).cwiseAbs().maxCoeff(),
              1e-14 * expected.cwiseAbs().maxCoeff());
  }
  Eigen::VectorXd f, f_r;
  sys.forces(q, v, 0.1, f);
  reduced.forces(q_r, v_r, 0.1, f_r);
  const Eigen::VectorXd expected = t.transpose() * f;
  EXPECT_LT((f_r - expected).cwiseAbs().maxCoeff(), 1e-14 * expected.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace mastrom::fullorder

namespace mastrom::fullorder {
namespace {

// The element forces may run on several threads (MultibodySystem::setThreadCount): every chunk has
// its own buffer and the buffers are summed in a fixed order, so the result is the same bit for
// bit; a degenerate element is still reported, whichever thread meets it.
TEST(MultibodySystem, ElementForcesOnTwoThreadsAreBitIdentical) {
  MastModel mast = buildMast(scheme(4, 1e-5));
  MultibodySystem& sys = mast.system();
  std::mt19937 gen(52);
  const Eigen::VectorXd q =
      mast.rotatedReference(0.3) + testing::randomVector(gen, sys.dofCount(), 1e-4);
  const Eigen::VectorXd qdot = testing::randomVector(gen, sys.dofCount(), 0.1);
  Eigen::VectorXd one, two;
  sys.forces(q, qdot, 0.2, one);
  sys.setThreadCount(2);
  EXPECT_EQ(sys.threadCount(), 2);
  sys.forces(q, qdot, 0.2, two);
  ASSERT_GT(one.cwiseAbs().maxCoeff(), 1.0);
  EXPECT_EQ((one - two).cwiseAbs().maxCoeff(), 0.0);

  // Collapse the last element to a point: its surface has no tangents.
  Eigen::VectorXd bad = q;
  const int last = sys.elementCount() - 1;
  for (int d : sys.elementDofs(last)) bad[d] = 0.0;
  try {
    sys.forces(bad, qdot, 0.2, two);
    FAIL() << "no error for a degenerate element";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate surface"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sys.setThreadCount(0), InputError);
}

TEST(MultibodySystem, ForcesAndConstraintsAtOnceEqualTheSeparateCalls) {
  // forcesAndConstraints overlaps Φ and Φ_q with the element forces on 2 and more threads (thread
  // 0 takes the constraints and fewer chunks): the values must not depend on that.
  MastModel mast = buildMast(scheme(4, 1e-5));
  MultibodySystem& sys = mast.system();
  std::mt19937 gen(53);
  const Eigen::VectorXd q =
      mast.rotatedReference(0.5) + testing::randomVector(gen, sys.dofCount(), 1e-4);
  const Eigen::VectorXd qdot = testing::randomVector(gen, sys.dofCount(), 0.1);
  Eigen::VectorXd f_ref, phi_ref;
  SparseMatrix g_ref;
  sys.forces(q, qdot, 0.7, f_ref);
  sys.constraints(q, 0.7, phi_ref);
  sys.constraintJacobian(q, 0.7, g_ref);
  ASSERT_GT(phi_ref.cwiseAbs().maxCoeff(), 0.0);
  for (int threads : {1, 2, 3}) {
    sys.setThreadCount(threads);
    Eigen::VectorXd f, phi;
    SparseMatrix g;
    sys.forcesAndConstraints(q, qdot, 0.7, f, phi, g);
    EXPECT_EQ((f - f_ref).cwiseAbs().maxCoeff(), 0.0) << threads << " threads";
    EXPECT_EQ((phi - phi_ref).cwiseAbs().maxCoeff(), 0.0) << threads << " threads";
    ASSERT_EQ(g.nonZeros(), g_ref.nonZeros());
    EXPECT_EQ(SparseMatrix(g - g_ref).coeffs().cwiseAbs().maxCoeff(), 0.0) << threads << " threads";
  }
  // A failure in the element forces is reported from the overlapped evaluation too.
  Eigen::VectorXd bad = q, f, phi;
  SparseMatrix g;
  for (int d : sys.elementDofs(0)) bad[d] = 0.0;
  sys.setThreadCount(2);
  EXPECT_THROW(sys.forcesAndConstraints(bad, qdot, 0.7, f, phi, g), NumericalError);
}

}  // namespace
}  // namespace mastrom::fullorder
