// The assembled mast (fullorder/mast_model.hpp): sizes of the paper's three schemes, the initial
// state, statics with the joint locked (no load: the reference; gravity: exact force and moment
// balance through the joint multipliers and a cantilever-tube estimate of the deflection).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>

#include "common/error.hpp"
#include "fullorder/mast_model.hpp"
#include "fullorder/static_solver.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(MastModel, SizesOfTheThreeSchemesAtTheDefaultMesh) {
  // n modules × 12 + (n − 1) interfaces × 3 rings × 8 nodes × 9;
  // n × 6 (modules) + 6 (joint) + (n − 1) × 2 rings × 8 nodes × 7 (bonded edges).
  const int expected_dofs[3] = {240, 468, 696};
  const int expected_constraints[3] = {130, 248, 366};
  for (int scheme = 1; scheme <= 3; ++scheme) {
    MastParameters p;
    p.modules = scheme + 1;
    const MastModel mast = buildMast(p);
    EXPECT_EQ(mast.dofCount(), expected_dofs[scheme - 1]) << "Scheme " << scheme;
    EXPECT_EQ(mast.constraintCount(), expected_constraints[scheme - 1]) << "Scheme " << scheme;
    EXPECT_EQ(mast.moduleCount(), scheme + 1);
    EXPECT_EQ(mast.interfaceCount(), scheme);
    EXPECT_EQ(mast.endModule(), scheme);
    EXPECT_EQ(mast.moduleDofOffset(mast.endModule()), 12 * scheme);
    EXPECT_EQ(mast.jointForceMultiplier(), 6 * (scheme + 1));
    EXPECT_EQ(mast.driveTorqueMultiplier(), 6 * (scheme + 1) + 5);
    for (int k = 0; k < mast.interfaceCount(); ++k) {
      const MastModel::InterfaceRange& r = mast.interfaceRange(k);
      EXPECT_EQ(r.node_count, 24);
      EXPECT_EQ(r.first_dof, 12 * (scheme + 1) + 9 * 24 * k);
      EXPECT_EQ(r.ring0_nodes.size(), 8u);
      EXPECT_EQ(r.ring1_nodes.size(), 8u);
    }
    // Mass: modules plus shells of ρh·(interpolated area ≈ 2πRL(1 − 5.2e-4)).
    const double shell = p.density_kg_m3 * p.interface_thickness_m * 2 * kPi *
                         p.interface_radius_m * p.interface_length_m;
    EXPECT_NEAR(mast.totalMass(), (scheme + 1) * p.module_mass_kg + scheme * shell,
                scheme * shell * 1e-3);
  }
}

TEST(MastModel, InitialStateSatisfiesTheConstraints) {
  MastParameters p;
  p.modules = 3;
  p.drive.kind = DriveLawKind::Cycloidal;
  MastModel mast = buildMast(p);
  Eigen::VectorXd q, qdot, phi, rhs;
  mast.initialState(q, qdot);
  mast.system().constraints(q, 0.0, phi);
  EXPECT_LT(phi.cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(qdot.norm(), 0.0);  // every drive law starts from rest

  p.lock_angle_rad = 0.6;
  MastModel locked = buildMast(p);
  locked.initialState(q, qdot);
  locked.system().constraints(q, 3.0, phi);
  EXPECT_LT(phi.cwiseAbs().maxCoeff(), 1e-15);
  // The end module points along θ₀.
  const Eigen::Vector3d end = q.segment<3>(locked.moduleDofOffset(locked.endModule()));
  EXPECT_NEAR(std::atan2(end.y(), end.x()), 0.6, 1e-15);
  EXPECT_NEAR(end.norm(), 2 * (p.module_side_m + p.interface_length_m), 1e-15);
}

TEST(MastModel, LockedUnloadedStaticsReturnsTheReference) {
  MastParameters p;
  p.modules = 4;
  p.lock_angle_rad = 0.3;
  const MastModel mast = buildMast(p);
  const Eigen::VectorXd q0 = mast.rotatedReference(0.3);
  const StaticResult r = solveStatic(mast.system(), q0);
  EXPECT_LE(r.iterations, 1);
  EXPECT_LT((r.q - q0).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT(r.lambda.cwiseAbs().maxCoeff(), 1e-6);
  std::cout << "[ mast statics ] no load: " << r.iterations
            << " iterations, |Δq| = " << (r.q - q0).cwiseAbs().maxCoeff()
            << ", |λ| = " << r.lambda.cwiseAbs().maxCoeff() << "\n";
}

TEST(MastModel, GravityStaticsOfSchemeOne) {
  MastParameters p;
  p.modules = 2;
  p.lock_angle_rad = 0.0;
  p.gravity_m_s2 = Eigen::Vector3d(0.0, -9.81, 0.0);
  const MastModel mast = buildMast(p);
  const MultibodySystem& sys = mast.system();
  const StaticResult r = solveStatic(sys, mast.rotatedReference(0.0));

  // Exact force balance: the only external forces are gravity and the joint, and every other
  // constraint and the elastic forces are invariant under translation, so F_joint = −m_total g.
  const Eigen::Vector3d weight = sys.totalMass() * p.gravity_m_s2;
  const Eigen::Vector3d force = mast.jointForce(r.lambda);
  EXPECT_LT((force + weight).norm(), 1e-9 * weight.norm())
      << "joint force " << force.transpose() << ", weight " << weight.transpose();
  // Exact moment balance about Z: the drive torque equals minus the moment of gravity about the
  // joint axis in the deformed configuration, −Q_g·(Z × q), positive (it holds the mast up).
  Eigen::VectorXd rot_mode(r.q.size());
  for (Eigen::Index k = 0; k < r.q.size() / 3; ++k)
    rot_mode.segment<3>(3 * k) =
        Eigen::Vector3d::UnitZ().cross(Eigen::Vector3d(r.q.segment<3>(3 * k)));
  const double gravity_moment = sys.gravityForce().dot(rot_mode);
  EXPECT_NEAR(mast.driveTorque(r.lambda), -gravity_moment, 1e-9 * std::abs(gravity_moment));
  EXPECT_GT(mast.driveTorque(r.lambda), 0.0);

  // Deflection of module 2's centroid against a Timoshenko cantilever-tube estimate: tube fixed at
  // module 1's face, tip load P = m g and moment P d/2 from module 2, own weight w = m_t g/L,
  // EI = πR³hE, shear κGA with κ = 1/2 (thin circular tube), A = 2πRh; the centroid is d/2 beyond
  // the tube end. L/R ≈ 1.2 is far from a slender beam and the bonded flanges stop ovalling, so
  // this is an order-of-magnitude check: ratio within [1/2, 2] (measured: 0.97).
  const double d = p.module_side_m, L = p.interface_length_m, R = p.interface_radius_m;
  const double h = p.interface_thickness_m, E = p.youngs_modulus_pa;
  const double G = E / (2.0 * (1.0 + p.poisson_ratio));
  const double ei = kPi * R * R * R * h * E, kga = 0.5 * G * 2.0 * kPi * R * h;
  const double P = p.module_mass_kg * 9.81, M = P * d / 2;
  const double w = (sys.totalMass() - 2 * p.module_mass_kg) * 9.81 / L;
  const double tip = P * L * L * L / (3 * ei) + M * L * L / (2 * ei) + P * L / kga +
                     w * L * L * L * L / (8 * ei) + w * L * L / (2 * kga);
  const double rotation = P * L * L / (2 * ei) + M * L / ei + w * L * L * L / (6 * ei);
  const double estimate = tip + rotation * d / 2;
  const Eigen::Vector3d c0 = mast.rotatedReference(0.0).segment<3>(mast.moduleDofOffset(1));
  const Eigen::Vector3d c = r.q.segment<3>(mast.moduleDofOffset(1));
  const double deflection = c0.y() - c.y();
  std::cout << "[ mast statics ] Scheme 1 under gravity: " << r.iterations << " Newton iterations; "
            << "module-2 deflection " << deflection << " m, cantilever-tube estimate " << estimate
            << " m (bending " << P * L * L * L / (3 * ei) + M * L * L / (2 * ei) << ", shear "
            << P * L / kga << ", rotation·d/2 " << rotation * d / 2 << "), ratio "
            << deflection / estimate << "\n"
            << "[ mast statics ] joint force " << force.transpose() << " N (weight "
            << weight.transpose() << "), relative error " << (force + weight).norm() / weight.norm()
            << "; drive torque " << mast.driveTorque(r.lambda) << " N·m, gravity moment "
            << gravity_moment << "\n";
  EXPECT_GT(deflection, 0.0);
  EXPECT_GT(deflection / estimate, 0.5);
  EXPECT_LT(deflection / estimate, 2.0);
  // In-plane gravity: no out-of-plane motion of the end module.
  EXPECT_LT(std::abs(c.z()), 1e-12);
}

TEST(MastModel, RejectsBadParameters) {
  MastParameters p;
  p.modules = 1;
  EXPECT_THROW(buildMast(p), InputError);
  p = MastParameters{};
  p.interface_thickness_m = 0.05;  // ≥ R
  EXPECT_THROW(buildMast(p), InputError);
  p = MastParameters{};
  p.poisson_ratio = 0.5;
  EXPECT_THROW(buildMast(p), InputError);
  p = MastParameters{};
  p.elements_circumferential = 2;
  EXPECT_THROW(buildMast(p), InputError);
  p = MastParameters{};
  p.drive.duration_s = -1.0;
  EXPECT_THROW(buildMast(p), InputError);
}

}  // namespace
}  // namespace mastrom::fullorder
