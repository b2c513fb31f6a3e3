// The six internal constraints of a rigid module in natural coordinates (docs/theory.md §2.1,
// [LW24] eq. 39) wrapped as a ConstraintBlock, so the system assembles them like any other block.
#pragma once

#include "fullorder/constraint.hpp"
#include "fullorder/ncf_body.hpp"

namespace mastrom::fullorder {

class ModuleConstraints final : public ConstraintBlock {
public:
  /// @param body        the module (copied; only d is used)
  /// @param dof_offset  global index of the module's first coordinate (r_i x)
  ModuleConstraints(const RigidModule& body, int dof_offset);

  std::string name() const override { return "rigid-module internal constraints"; }
  void evaluate(const ConstVec& q, double t, Eigen::Ref<Eigen::VectorXd> phi) const override;
  void jacobian(const ConstVec& q, double t, Eigen::Ref<Eigen::MatrixXd> jac) const override;
  /// Quadratic constraints: the Hessian term is constant in q, linear in λ.
  bool hasHessianTerm() const override { return true; }
  void hessianTerm(const ConstVec& q, const ConstVec& lambda, double t,
                   Eigen::Ref<Eigen::MatrixXd> h) const override;
  void velocityTerm(const ConstVec& q, const ConstVec& qdot, double t,
                    Eigen::Ref<Eigen::VectorXd> gamma) const override;
  /// Lengths and dot products of the body's vectors: all six rows are invariant under rotation.
  std::optional<std::vector<int>> rotatingRowTriples() const override {
    return std::vector<int>{};
  }

private:
  RigidModule body_;
};

}  // namespace mastrom::fullorder
