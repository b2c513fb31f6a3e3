// Base joint and drive (fullorder/base_joint.hpp, docs/theory.md §2.4): the equations hold exactly
// on the rotation θ(t) about Z; Jacobian, Φ_t, Φ_tt and the velocity term against (central)
// differences; the joint-force and drive-torque accessors against the virtual work of the
// constraint forces.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "assembly_test_helpers.hpp"
#include "fullorder/base_joint.hpp"
#include "fullorder/ncf_body.hpp"

namespace mastrom::fullorder {
namespace {

using testing::centralJacobian;
using testing::evaluateBlock;
using testing::jacobianOf;

constexpr double kPi = 3.14159265358979323846;

Eigen::Matrix3d rotationZ(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

DriveLaw cycloidal() {
  DriveLawParameters p;
  p.kind = DriveLawKind::Cycloidal;
  p.total_angle_rad = kPi / 2;
  p.duration_s = 2.0;
  return DriveLaw(p);
}

const RigidModule kModule(0.1, 0.5, RigidModule::boxInertia(0.5, 0.1, 0.1, 0.1));

Eigen::VectorXd poseAt(double angle) {
  return kModule.coordinates(Eigen::Vector3d::Zero(), rotationZ(angle));
}

/// δq of an infinitesimal rotation about Z through the origin (every 3-block b ↦ Z × b).
Eigen::VectorXd rotationMode(const Eigen::VectorXd& q) {
  Eigen::VectorXd d(12);
  for (int k = 0; k < 4; ++k)
    d.segment<3>(3 * k) = Eigen::Vector3d::UnitZ().cross(Eigen::Vector3d(q.segment<3>(3 * k)));
  return d;
}

Eigen::VectorXd translationMode(const Eigen::Vector3d& v) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(12);
  d.head<3>() = v;
  d.segment<3>(3) = v;
  return d;
}

TEST(BaseJoint, HoldsExactlyOnThePrescribedRotation) {
  const DriveLaw law = cycloidal();
  const BaseJoint joint(0, 0.1, law);
  EXPECT_TRUE(joint.isTimeDependent());
  EXPECT_FALSE(joint.hasHessianTerm());
  for (double t : {0.0, 0.4, 1.1, 2.0, 3.0}) {
    const double theta = law.at(t).angle_rad;
    EXPECT_LT(evaluateBlock(joint, poseAt(theta), t).cwiseAbs().maxCoeff(), 1e-16) << "t = " << t;
    // A wrong angle violates only the drive row, by sin(θ' − θ).
    const Eigen::VectorXd phi = evaluateBlock(joint, poseAt(theta + 0.2), t);
    EXPECT_LT(phi.head<5>().cwiseAbs().maxCoeff(), 1e-16);
    EXPECT_NEAR(phi[5], std::sin(0.2), 1e-15);
  }
  // Tilting out of the X–Y plane or moving the centroid violates the other rows.
  const Eigen::VectorXd tilted = kModule.coordinates(
      Eigen::Vector3d::Zero(), Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()).toRotationMatrix());
  EXPECT_NEAR(evaluateBlock(joint, tilted, 0.0)[3], std::sin(0.1), 1e-15);  // u·Z
  const Eigen::VectorXd shifted =
      kModule.coordinates(Eigen::Vector3d(0.01, 0.0, 0.0), Eigen::Matrix3d::Identity());
  EXPECT_NEAR(evaluateBlock(joint, shifted, 0.0)[0], 0.01, 1e-17);
}

TEST(BaseJoint, DerivativesAgreeWithDifferences) {
  std::mt19937 gen(21);
  const DriveLaw law = cycloidal();
  const BaseJoint joint(0, 0.1, law);
  const double t = 0.7;
  const Eigen::VectorXd q = poseAt(0.5) + testing::randomVector(gen, 12, 0.05);
  const Eigen::VectorXd qdot = testing::randomVector(gen, 12, 0.3);

  // Φ is linear in q: central differences exact up to round-off (~1e-11 on O(10) entries).
  const Eigen::MatrixXd jac = jacobianOf(joint, q, t);
  const Eigen::MatrixXd jac_fd =
      centralJacobian([&](const Eigen::VectorXd& x) { return evaluateBlock(joint, x, t); }, q);
  EXPECT_LT((jac - jac_fd).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_TRUE(testing::insideStructure(jac, joint.jacobianStructure()));

  // Φ_t: central difference in t with h = ∛ε·T; truncation h²|Φ_ttt|/6 with |Φ_ttt| ≲ Θ(2π/T)³ ≈ 50
  // gives ≈ 1e-9; round-off ε/h ≈ 1e-11.
  Eigen::VectorXd phi_t(6), phi_tt(6), gamma(6);
  joint.timeDerivative(q, t, phi_t);
  const double ht = testing::kCbrtEps * 2.0;
  const Eigen::VectorXd phi_t_fd =
      (evaluateBlock(joint, q, t + ht) - evaluateBlock(joint, q, t - ht)) / (2 * ht);
  EXPECT_LT((phi_t - phi_t_fd).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_GT(std::abs(phi_t[5]), 0.1);  // the check is not vacuous

  // Φ_tt: second difference with h = 3e-4 s; truncation h²|Φ''''|/12 ≲ 1e-8·300/12, round-off
  // 4ε/h² ≈ 1e-8: tolerance 1e-6 on |Φ_tt| ≈ 1.
  joint.secondTimeDerivative(q, t, phi_tt);
  const double h2 = 3e-4;
  const Eigen::VectorXd phi_tt_fd =
      (evaluateBlock(joint, q, t + h2) - 2 * evaluateBlock(joint, q, t) +
       evaluateBlock(joint, q, t - h2)) /
      (h2 * h2);
  EXPECT_LT((phi_tt - phi_tt_fd).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_GT(std::abs(phi_tt[5]), 0.1);

  // Along the path (q + s q̇, t + s): d²Φ/ds² = γ_v + Φ_tt (same difference and tolerance).
  joint.velocityTerm(q, qdot, t, gamma);
  const Eigen::VectorXd path_fd =
      (evaluateBlock(joint, q + h2 * qdot, t + h2) - 2 * evaluateBlock(joint, q, t) +
       evaluateBlock(joint, q - h2 * qdot, t - h2)) /
      (h2 * h2);
  EXPECT_LT((gamma + phi_tt - path_fd).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_GT(std::abs(gamma[5]), 1e-3);
}

TEST(BaseJoint, LockedJointIsStatic) {
  const BaseJoint joint(0, 0.1, LockedAngle{0.4});
  EXPECT_TRUE(joint.isLocked());
  EXPECT_FALSE(joint.isTimeDependent());
  EXPECT_LT(evaluateBlock(joint, poseAt(0.4), 5.0).cwiseAbs().maxCoeff(), 1e-16);
  Eigen::VectorXd v(6);
  joint.timeDerivative(poseAt(0.4), 1.0, v);
  EXPECT_EQ(v.norm(), 0.0);
  joint.velocityTerm(poseAt(0.4), Eigen::VectorXd::Ones(12), 1.0, v);
  EXPECT_EQ(v.norm(), 0.0);
  EXPECT_DOUBLE_EQ(joint.driveAt(3.0).angle_rad, 0.4);
}

TEST(BaseJoint, AccessorsMatchTheVirtualWorkOfTheConstraintForces) {
  // With M q̈ + Φ_qᵀλ = Q the constraint force is −Φ_qᵀλ. Its virtual work on a rigid translation v
  // of module 1 is the joint force · v; on a rigid rotation δα about Z it is the drive torque · δα.
  std::mt19937 gen(22);
  const DriveLaw law = cycloidal();
  const BaseJoint joint(0, 0.1, law);
  const double t = 0.9;
  const Eigen::VectorXd q = poseAt(law.at(t).angle_rad);
  const Eigen::MatrixXd jac = jacobianOf(joint, q, t);
  const Eigen::VectorXd lambda = testing::randomVector(gen, 6, 10.0);
  const Eigen::VectorXd constraint_force = -jac.transpose() * lambda;
  const Eigen::Vector3d force = BaseJoint::jointForce(lambda);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(constraint_force.dot(translationMode(Eigen::Vector3d::Unit(k))), force[k], 1e-13);
  EXPECT_NEAR(constraint_force.dot(rotationMode(q)), BaseJoint::driveTorque(lambda), 1e-13);
  // The rotation mode changes only the drive row, at unit rate (λ₅ is a torque in N·m).
  const Eigen::VectorXd rate = jac * rotationMode(q);
  EXPECT_LT(rate.head<5>().cwiseAbs().maxCoeff(), 1e-16);
  EXPECT_NEAR(rate[5], 1.0, 1e-15);
}

}  // namespace
}  // namespace mastrom::fullorder
