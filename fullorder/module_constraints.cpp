// Rigid-module internal constraints as a block (see module_constraints.hpp).
#include "fullorder/module_constraints.hpp"

#include <numeric>

namespace mastrom::fullorder {
namespace {
std::vector<int> consecutive(int first, int count) {
  std::vector<int> v(static_cast<size_t>(count));
  std::iota(v.begin(), v.end(), first);
  return v;
}
}  // namespace

ModuleConstraints::ModuleConstraints(const RigidModule& body, int dof_offset)
    : ConstraintBlock(RigidModule::kConstraints, consecutive(dof_offset, RigidModule::kDofs)),
      body_(body) {}

void ModuleConstraints::evaluate(const ConstVec& q, double, Eigen::Ref<Eigen::VectorXd> phi) const {
  phi = body_.constraints(Vec12(q));
}

void ModuleConstraints::jacobian(const ConstVec& q, double, Eigen::Ref<Eigen::MatrixXd> jac) const {
  jac = body_.constraintJacobian(Vec12(q));
}

void ModuleConstraints::hessianTerm(const ConstVec&, const ConstVec& lambda, double,
                                    Eigen::Ref<Eigen::MatrixXd> h) const {
  h = body_.constraintHessianTerm(Vec6(lambda));
}

void ModuleConstraints::velocityTerm(const ConstVec&, const ConstVec& qdot, double,
                                     Eigen::Ref<Eigen::VectorXd> gamma) const {
  gamma = body_.constraintQuadraticVelocityTerm(Vec12(qdot));
}

}  // namespace mastrom::fullorder
