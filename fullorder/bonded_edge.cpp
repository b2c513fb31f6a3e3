// Bonded edge node (see bonded_edge.hpp; docs/theory.md §2.3).
#include "fullorder/bonded_edge.hpp"

#include <numeric>

namespace mastrom::fullorder {
namespace {

std::vector<int> localDofs(int body_offset, int node_offset, bool with_body) {
  std::vector<int> dofs;
  if (with_body)
    for (int k = 0; k < RigidModule::kDofs; ++k) dofs.push_back(body_offset + k);
  for (int k = 0; k < 9; ++k) dofs.push_back(node_offset + k);
  return dofs;
}

/// A ground frame described as an NCF body with a 1 m axis (only its maps are used).
RigidModule groundMapBody() { return RigidModule(1.0, 1.0, Eigen::Matrix3d::Identity()); }

}  // namespace

BondedEdgeNode::BondedEdgeNode(const RigidModule& body, int body_dof_offset,
                               const Vec12& body_reference, int node_dof_offset,
                               const Vec9& node_reference, const Eigen::Vector3d& node_normal)
    : ConstraintBlock(kEquations, localDofs(body_dof_offset, node_dof_offset, true)),
      grounded_(false) {
  setLocalData(body, body_reference, node_reference, node_normal);
}

BondedEdgeNode::BondedEdgeNode(const GroundFrame& ground, int node_dof_offset,
                               const Vec9& node_reference, const Eigen::Vector3d& node_normal)
    : ConstraintBlock(kEquations, localDofs(0, node_dof_offset, false)), grounded_(true) {
  const RigidModule frame = groundMapBody();
  ground_q_ = frame.coordinates(ground.origin, ground.rotation);
  setLocalData(frame, ground_q_, node_reference, node_normal);
}

void BondedEdgeNode::setLocalData(const RigidModule& frame, const Vec12& frame_reference,
                                  const Vec9& node_reference, const Eigen::Vector3d& node_normal) {
  const Eigen::Matrix3d rot = frame.rotation(frame_reference);
  const Eigen::Vector3d centroid = frame_reference.head<3>();
  c_ = rot.transpose() * (node_reference.head<3>() - centroid);
  t_ = rot.transpose() * node_reference.tail<3>();
  n_ = rot.transpose() * node_normal.normalized();
  a_point_ = frame.pointMap(c_);
  a_tangent_ = frame.directionMap(t_);
  a_normal_ = frame.directionMap(n_);
}

std::string BondedEdgeNode::name() const {
  return grounded_ ? "bonded edge node (ground)" : "bonded edge node (module)";
}

Vec12 BondedEdgeNode::bodyCoordinates(const ConstVec& q) const {
  return grounded_ ? ground_q_ : Vec12(q.head<RigidModule::kDofs>());
}

void BondedEdgeNode::evaluate(const ConstVec& q, double, Eigen::Ref<Eigen::VectorXd> phi) const {
  const Vec12 qr = bodyCoordinates(q);
  const int o = nodeOffset();
  phi.segment<3>(0) = q.segment<3>(o) - a_point_ * qr;
  phi.segment<3>(3) = q.segment<3>(o + 6) - a_tangent_ * qr;
  phi[6] = q.segment<3>(o + 3).dot(a_normal_ * qr);
}

void BondedEdgeNode::jacobian(const ConstVec& q, double, Eigen::Ref<Eigen::MatrixXd> jac) const {
  const Vec12 qr = bodyCoordinates(q);
  const int o = nodeOffset();
  // Every structural entry is written below; the rest stays zero (ConstraintBlock::jacobian).
  jac.block<3, 3>(0, o).setIdentity();
  jac.block<3, 3>(3, o + 6).setIdentity();
  jac.block<1, 3>(6, o + 3) = (a_normal_ * qr).transpose();
  if (!grounded_) {
    jac.block<3, 12>(0, 0) = -a_point_;
    jac.block<3, 12>(3, 0) = -a_tangent_;
    jac.block<1, 12>(6, 0) = q.segment<3>(o + 3).transpose() * a_normal_;
  }
}

void BondedEdgeNode::hessianTerm(const ConstVec&, const ConstVec& lambda, double,
                                 Eigen::Ref<Eigen::MatrixXd> h) const {
  h.setZero();
  if (grounded_) return;
  // ∂²(λ₆ r_x·A_n q_r)/∂(r_x, q_r): only the off-diagonal coupling blocks.
  const int o = nodeOffset();
  h.block<3, 12>(o + 3, 0) = lambda[6] * a_normal_;
  h.block<12, 3>(0, o + 3) = lambda[6] * a_normal_.transpose();
}

void BondedEdgeNode::velocityTerm(const ConstVec&, const ConstVec& qdot, double,
                                  Eigen::Ref<Eigen::VectorXd> gamma) const {
  gamma.setZero();
  if (grounded_) return;
  // (Φ₆,q q̇)_q q̇ = 2 ṙ_x·(A_n q̇_r); the other rows are linear.
  const int o = nodeOffset();
  gamma[6] = 2.0 * qdot.segment<3>(o + 3).dot(a_normal_ * qdot.head<12>());
}

BoolMatrix BondedEdgeNode::jacobianStructure() const {
  const int o = nodeOffset();
  BoolMatrix s = BoolMatrix::Constant(kEquations, localDofCount(), false);
  for (int i = 0; i < 3; ++i) {
    s(i, o + i) = true;
    s(3 + i, o + 6 + i) = true;
    s(6, o + 3 + i) = true;
  }
  if (!grounded_) {
    for (int j = 0; j < 12; ++j) {
      for (int i = 0; i < 3; ++i) {
        s(i, j) = a_point_(i, j) != 0.0;
        s(3 + i, j) = a_tangent_(i, j) != 0.0;
        s(6, j) = s(6, j) || a_normal_(i, j) != 0.0;
      }
    }
  }
  return s;
}

BoolMatrix BondedEdgeNode::hessianStructure() const {
  BoolMatrix s = BoolMatrix::Constant(localDofCount(), localDofCount(), false);
  if (grounded_) return s;
  const int o = nodeOffset();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 12; ++j) {
      s(o + 3 + i, j) = a_normal_(i, j) != 0.0;
      s(j, o + 3 + i) = a_normal_(i, j) != 0.0;
    }
  }
  return s;
}

}  // namespace mastrom::fullorder
