// Base joint and drive of module 1 (docs/theory.md §2.4; [LW24] eq. 41).
//
// Module 1 (q = [r_i, r_j, u, v], axis length d) may only rotate about the global Z axis through
// the origin, by the prescribed angle θ(t). Six equations, all linear in q:
//   row 0..2  r_i = 0                        pin: module 1's centroid stays at the origin
//   row 3     u·Z = 0                        } the module's x̂ and ŷ stay in the X–Y plane
//   row 4     (r_j − r_i)·Z = 0              }
//   row 5     x̂·ŝ(θ(t)) = 0,  x̂ = (r_j − r_i)/d,  ŝ(θ) = (−sin θ, cos θ, 0)     drive
// With the internal constraints of the module these fix x̂ = (cos θ, sin θ, 0), u = (−sin θ, cos θ,
// 0) (on the branch connected to the stowed state), v = Z.
//
// Multipliers (convention M q̈ + Φ_qᵀλ = Q, constraint force −Φ_qᵀλ):
// * Joint force. Only rows 0..2 have a resultant: the gradients of rows 3..5 sum to zero over r_i
// and
//   r_j, so they are pure couples. The joint force ON module 1 is F = −λ[0:3] [N], global frame.
// * Drive torque. For a virtual rotation δα about Z (δr_j = Z × r_j δα, δu = Z × u δα, …; δr_i = 0
//   since r_i = 0) rows 0..4 do not change and δΦ₅ = (Z × x̂)·ŝ δα = ŝ·ŝ δα = δα. The constraint
//   forces' virtual work is −λ₅ δα, so the drive applies the torque τ = −λ₅ [N·m] to module 1 about
//   +Z (positive when the drive accelerates the mast towards +θ). Φ₅ is dimensionless, hence λ₅ in
//   N·m.
// Locked mode (statics, modes): θ(t) ≡ θ₀ and the block is time-independent.
#pragma once

#include "fullorder/constraint.hpp"
#include "fullorder/drive_law.hpp"

namespace mastrom::fullorder {

/// Tag for a joint locked at a constant angle.
struct LockedAngle {
  double angle_rad = 0.0;
};

class BaseJoint final : public ConstraintBlock {
public:
  static constexpr int kEquations = 6;
  static constexpr int kPinRow = 0;    ///< first of the three pin rows (joint force)
  static constexpr int kDriveRow = 5;  ///< the driving constraint (drive torque)

  /// Driven joint on the module whose 12 coordinates start at body_dof_offset (axis length d).
  BaseJoint(int body_dof_offset, double axis_length_m, const DriveLaw& drive);
  /// Joint locked at a constant angle.
  BaseJoint(int body_dof_offset, double axis_length_m, LockedAngle lock);

  std::string name() const override { return "base joint and drive"; }
  bool isLocked() const { return locked_; }
  /// θ, θ̇, θ̈ at time t (constant θ₀ and zero rates when locked).
  DriveState driveAt(double t) const;
  /// The drive law (the default law when locked).
  const DriveLaw& driveLaw() const { return drive_; }

  void evaluate(const ConstVec& q, double t, Eigen::Ref<Eigen::VectorXd> phi) const override;
  void jacobian(const ConstVec& q, double t, Eigen::Ref<Eigen::MatrixXd> jac) const override;
  bool hasHessianTerm() const override { return false; }
  bool isTimeDependent() const override { return !locked_; }
  void timeDerivative(const ConstVec& q, double t,
                      Eigen::Ref<Eigen::VectorXd> phi_t) const override;
  void secondTimeDerivative(const ConstVec& q, double t,
                            Eigen::Ref<Eigen::VectorXd> phi_tt) const override;
  void velocityTerm(const ConstVec& q, const ConstVec& qdot, double t,
                    Eigen::Ref<Eigen::VectorXd> gamma) const override;
  BoolMatrix jacobianStructure() const override;
  /// The pin rows 0..2 are a vector; rows 3..5 are invariant under a turn about Z that advances
  /// θ(t) by as much (row 5 compares the body's x̂ with ŝ(θ(t)), both turned).
  std::optional<std::vector<int>> rotatingRowTriples() const override {
    return std::vector<int>{kPinRow};
  }
  double frameAngle(double t) const override { return driveAt(t).angle_rad; }

  /// Force of the joint on module 1 [N], global, from this block's six multipliers.
  static Eigen::Vector3d jointForce(const Eigen::Ref<const Eigen::VectorXd>& block_lambda);
  /// Torque the drive applies to module 1 about +Z [N·m], from this block's six multipliers.
  static double driveTorque(const Eigen::Ref<const Eigen::VectorXd>& block_lambda);

private:
  double d_;
  bool locked_;
  double lock_angle_rad_ = 0.0;
  DriveLaw drive_;
};

}  // namespace mastrom::fullorder
