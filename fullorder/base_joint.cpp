// Base joint and drive (see base_joint.hpp; docs/theory.md §2.4).
#include "fullorder/base_joint.hpp"

#include <cmath>
#include <numeric>

#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {

std::vector<int> moduleDofs(int offset) {
  std::vector<int> v(12);
  std::iota(v.begin(), v.end(), offset);
  return v;
}

// ŝ(θ) and its θ-derivatives: ŝ' = (−cos θ, −sin θ, 0), ŝ'' = −ŝ.
Eigen::Vector3d sHat(double th) { return {-std::sin(th), std::cos(th), 0.0}; }
Eigen::Vector3d sHatPrime(double th) { return {-std::cos(th), -std::sin(th), 0.0}; }

// Local layout of module coordinates.
constexpr int kRi = 0, kRj = 3, kU = 6;

}  // namespace

BaseJoint::BaseJoint(int body_dof_offset, double axis_length_m, const DriveLaw& drive)
    : ConstraintBlock(kEquations, moduleDofs(body_dof_offset)),
      d_(axis_length_m),
      locked_(false),
      drive_(drive) {
  MASTROM_REQUIRE(std::isfinite(d_) && d_ > 0.0, InputError, "base joint: axis_length_m = ", d_,
                  " is out of range (must be > 0)");
}

BaseJoint::BaseJoint(int body_dof_offset, double axis_length_m, LockedAngle lock)
    : ConstraintBlock(kEquations, moduleDofs(body_dof_offset)),
      d_(axis_length_m),
      locked_(true),
      lock_angle_rad_(lock.angle_rad),
      drive_(DriveLawParameters{}) {
  MASTROM_REQUIRE(std::isfinite(d_) && d_ > 0.0, InputError, "base joint: axis_length_m = ", d_,
                  " is out of range (must be > 0)");
  MASTROM_REQUIRE(std::isfinite(lock_angle_rad_), InputError,
                  "base joint: lock angle = ", lock_angle_rad_, " is not finite");
}

DriveState BaseJoint::driveAt(double t) const {
  if (locked_) return DriveState{lock_angle_rad_, 0.0, 0.0};
  return drive_.at(t);
}

void BaseJoint::evaluate(const ConstVec& q, double t, Eigen::Ref<Eigen::VectorXd> phi) const {
  const Eigen::Vector3d ri = q.segment<3>(kRi), rj = q.segment<3>(kRj), u = q.segment<3>(kU);
  const double theta = driveAt(t).angle_rad;
  phi.segment<3>(0) = ri;
  phi[3] = u.z();
  phi[4] = rj.z() - ri.z();
  phi[5] = (rj - ri).dot(sHat(theta)) / d_;
}

void BaseJoint::jacobian(const ConstVec&, double t, Eigen::Ref<Eigen::MatrixXd> jac) const {
  const Eigen::Vector3d s = sHat(driveAt(t).angle_rad) / d_;
  jac.setZero();
  jac.block<3, 3>(0, kRi).setIdentity();
  jac(3, kU + 2) = 1.0;
  jac(4, kRi + 2) = -1.0;
  jac(4, kRj + 2) = 1.0;
  jac.block<1, 3>(5, kRi) = -s.transpose();
  jac.block<1, 3>(5, kRj) = s.transpose();
}

void BaseJoint::timeDerivative(const ConstVec& q, double t,
                               Eigen::Ref<Eigen::VectorXd> phi_t) const {
  phi_t.setZero();
  if (locked_) return;
  const DriveState ds = drive_.at(t);
  const Eigen::Vector3d x = (q.segment<3>(kRj) - q.segment<3>(kRi)) / d_;
  phi_t[5] = x.dot(sHatPrime(ds.angle_rad)) * ds.rate_rad_s;
}

void BaseJoint::secondTimeDerivative(const ConstVec& q, double t,
                                     Eigen::Ref<Eigen::VectorXd> phi_tt) const {
  phi_tt.setZero();
  if (locked_) return;
  const DriveState ds = drive_.at(t);
  const Eigen::Vector3d x = (q.segment<3>(kRj) - q.segment<3>(kRi)) / d_;
  // d²ŝ/dt² = ŝ'' θ̇² + ŝ' θ̈ with ŝ'' = −ŝ.
  phi_tt[5] = x.dot(-sHat(ds.angle_rad) * ds.rate_rad_s * ds.rate_rad_s +
                    sHatPrime(ds.angle_rad) * ds.acceleration_rad_s2);
}

void BaseJoint::velocityTerm(const ConstVec&, const ConstVec& qdot, double t,
                             Eigen::Ref<Eigen::VectorXd> gamma) const {
  gamma.setZero();
  if (locked_) return;
  // Φ is linear in q: (Φ_q q̇)_q = 0; the mixed term 2 Φ_qt q̇ remains for the drive row.
  const DriveState ds = drive_.at(t);
  const Eigen::Vector3d xdot = (qdot.segment<3>(kRj) - qdot.segment<3>(kRi)) / d_;
  gamma[5] = 2.0 * xdot.dot(sHatPrime(ds.angle_rad)) * ds.rate_rad_s;
}

BoolMatrix BaseJoint::jacobianStructure() const {
  BoolMatrix s = BoolMatrix::Constant(kEquations, localDofCount(), false);
  for (int i = 0; i < 3; ++i) s(i, kRi + i) = true;
  s(3, kU + 2) = true;
  s(4, kRi + 2) = s(4, kRj + 2) = true;
  // The drive row's z entries are zero for every θ (ŝ has no Z component).
  for (int i = 0; i < 2; ++i) s(5, kRi + i) = s(5, kRj + i) = true;
  return s;
}

Eigen::Vector3d BaseJoint::jointForce(const Eigen::Ref<const Eigen::VectorXd>& block_lambda) {
  return -block_lambda.segment<3>(kPinRow);
}

double BaseJoint::driveTorque(const Eigen::Ref<const Eigen::VectorXd>& block_lambda) {
  return -block_lambda[kDriveRow];
}

}  // namespace mastrom::fullorder
