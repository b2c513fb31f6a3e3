// Bonded edge: one shell node clamped to a rigid flange (docs/theory.md §2.3, replacing [LW24] eq.
// 40).
//
// For a node with reference data e₀ = [r⁰, r⁰_x, r⁰_y] and reference unit normal n⁰, bonded to a
// body with reference coordinates q_r⁰ (centroid r⁰_i, rotation R⁰ = [x̂, u, v]), the constant local
// data
//   c = R⁰ᵀ(r⁰ − r⁰_i),  t = R⁰ᵀ r⁰_y,  n = R⁰ᵀ n⁰
// are computed once. Seven equations per node (with A, A_dir the maps of fullorder/ncf_body.hpp):
//   r   − A(c) q_r       = 0   (3, linear)      the wall point moves with the flange
//   r_y − A_dir(t) q_r   = 0   (3, linear)      the edge tangent moves with the flange (no hoop
//   strain) r_x · A_dir(n) q_r   = 0   (1, bilinear)    the wall may not rotate about the edge
// r_x is otherwise free: the wall may still stretch axially and shear at the edge.
// All seven are invariant under a common rigid motion of body and shell.
//
// The same equations with a constant q_r bond a node to a fixed ground frame (the clamped strip of
// the static tests): then the block touches only the node's nine coordinates and is linear.
// Multipliers: with M q̈ + Φ_qᵀλ = Q, the force of the flange on the node's position is −λ[0:3] [N],
// the force couple on r_y is −λ[3:6] [N·m] and −λ[6] [N·m] is the clamping moment per unit slope.
#pragma once

#include "fullorder/constraint.hpp"
#include "fullorder/ncf_body.hpp"

namespace mastrom::fullorder {

using Vec9 = Eigen::Matrix<double, 9, 1>;

/// A fixed rigid frame (ground): global = origin + rotation · local.
struct GroundFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
};

class BondedEdgeNode final : public ConstraintBlock {
public:
  static constexpr int kEquations = 7;

  /// Node bonded to a rigid module. Local DOFs: [q_r (12), e_node (9)].
  /// @param body_reference  q_r⁰, the body's coordinates in the reference configuration
  /// @param node_reference  e₀ of the node in the same reference configuration
  /// @param node_normal     reference unit normal n⁰ (its sign is irrelevant)
  BondedEdgeNode(const RigidModule& body, int body_dof_offset, const Vec12& body_reference,
                 int node_dof_offset, const Vec9& node_reference,
                 const Eigen::Vector3d& node_normal);

  /// Node bonded to a fixed ground frame. Local DOFs: [e_node (9)].
  BondedEdgeNode(const GroundFrame& ground, int node_dof_offset, const Vec9& node_reference,
                 const Eigen::Vector3d& node_normal);

  std::string name() const override;
  bool isGrounded() const { return grounded_; }
  const Eigen::Vector3d& localPosition() const { return c_; }
  const Eigen::Vector3d& localTangent() const { return t_; }
  const Eigen::Vector3d& localNormal() const { return n_; }

  void evaluate(const ConstVec& q, double t, Eigen::Ref<Eigen::VectorXd> phi) const override;
  void jacobian(const ConstVec& q, double t, Eigen::Ref<Eigen::MatrixXd> jac) const override;
  /// Bilinear in (r_x, q_r) when bonded to a body; linear when grounded.
  bool hasHessianTerm() const override { return !grounded_; }
  void hessianTerm(const ConstVec& q, const ConstVec& lambda, double t,
                   Eigen::Ref<Eigen::MatrixXd> h) const override;
  /// Bonded to a body: the r and r_y rows are vectors, the slope clamp is a scalar (all seven are
  /// invariant under a common rigid motion, see above). Grounded: the fixed frame breaks it.
  std::optional<std::vector<int>> rotatingRowTriples() const override {
    if (grounded_) return std::nullopt;
    return std::vector<int>{0, 3};
  }
  void velocityTerm(const ConstVec& q, const ConstVec& qdot, double t,
                    Eigen::Ref<Eigen::VectorXd> gamma) const override;
  BoolMatrix jacobianStructure() const override;
  BoolMatrix hessianStructure() const override;

private:
  void setLocalData(const RigidModule& frame, const Vec12& frame_reference,
                    const Vec9& node_reference, const Eigen::Vector3d& node_normal);
  /// Body coordinates: the local ones, or the constant ground coordinates.
  Vec12 bodyCoordinates(const ConstVec& q) const;
  int nodeOffset() const { return grounded_ ? 0 : RigidModule::kDofs; }

  bool grounded_;
  Vec12 ground_q_ = Vec12::Zero();  ///< coordinates of the ground frame (grounded only)
  Eigen::Vector3d c_, t_, n_;       ///< local position, edge tangent, normal
  Mat3x12 a_point_, a_tangent_, a_normal_;
};

}  // namespace mastrom::fullorder
