// Constraints, their derivatives and the iteration matrix of the multibody system, scattered into
// the fixed sparsity patterns finalize() built, and the DaeSystem interface the integrator calls
// (see multibody_system.hpp; docs/theory.md §5.1).
#include <algorithm>
#include <functional>

#include "common/error.hpp"
#include "fullorder/multibody_system.hpp"
#include "fullorder/two_threads.hpp"

namespace mastrom::fullorder {
namespace {

/// Whether `h` already carries the pattern of `pattern` (same shape and structure).
bool hasPattern(const SparseMatrix& h, const SparseMatrix& pattern) {
  return h.rows() == pattern.rows() && h.cols() == pattern.cols() && h.isCompressed() &&
         h.nonZeros() == pattern.nonZeros() &&
         std::equal(h.outerIndexPtr(), h.outerIndexPtr() + h.cols() + 1, pattern.outerIndexPtr()) &&
         std::equal(h.innerIndexPtr(), h.innerIndexPtr() + h.nonZeros(), pattern.innerIndexPtr());
}

}  // namespace

// ============================================================================ constraints

void MultibodySystem::constraints(const ConstVec& q, double t, Eigen::VectorXd& phi) const {
  requireFinalized("constraints()");
  constraintsWith(block_scratch_, q, t, phi);
}

void MultibodySystem::constraintsWith(std::vector<BlockScratch>& scratch, const ConstVec& q,
                                      double t, Eigen::VectorXd& phi) const {
  phi.resize(constraintCount());
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    BlockScratch& s = scratch[k];
    gather(block, q, s.q);
    block.evaluate(s.q, t, phi.segment(constraint_offset_[k], block.size()));
  }
}

void MultibodySystem::constraintJacobian(const ConstVec& q, double t, SparseMatrix& g) const {
  requireFinalized("constraintJacobian()");
  constraintJacobianWith(block_scratch_, q, t, g);
}

void MultibodySystem::constraintJacobianWith(std::vector<BlockScratch>& scratch, const ConstVec& q,
                                             double t, SparseMatrix& g) const {
  if (!hasPattern(g, g_pattern_)) g = g_pattern_;
  double* values = g.valuePtr();
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    BlockScratch& s = scratch[k];
    gather(block, q, s.q);
    block.jacobian(s.q, t, s.jac);
    const Scatter& sc = jac_in_g_[k];
    for (size_t i = 0; i < sc.local.size(); ++i) values[sc.position[i]] = s.jac.data()[sc.local[i]];
  }
}

void MultibodySystem::constraintTimeDerivative(const ConstVec& q, double t,
                                               Eigen::VectorXd& phi_t) const {
  requireFinalized("constraintTimeDerivative()");
  phi_t.setZero(constraintCount());
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    if (!block.isTimeDependent()) continue;
    BlockScratch& s = block_scratch_[k];
    gather(block, q, s.q);
    block.timeDerivative(s.q, t, phi_t.segment(constraint_offset_[k], block.size()));
  }
}

void MultibodySystem::constraintSecondTimeDerivative(const ConstVec& q, double t,
                                                     Eigen::VectorXd& phi_tt) const {
  requireFinalized("constraintSecondTimeDerivative()");
  phi_tt.setZero(constraintCount());
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    if (!block.isTimeDependent()) continue;
    BlockScratch& s = block_scratch_[k];
    gather(block, q, s.q);
    block.secondTimeDerivative(s.q, t, phi_tt.segment(constraint_offset_[k], block.size()));
  }
}

void MultibodySystem::constraintVelocityTerm(const ConstVec& q, const ConstVec& qdot, double t,
                                             Eigen::VectorXd& gamma) const {
  requireFinalized("constraintVelocityTerm()");
  gamma.resize(constraintCount());
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    BlockScratch& s = block_scratch_[k];
    gather(block, q, s.q);
    gather(block, qdot, s.qdot);
    block.velocityTerm(s.q, s.qdot, t, gamma.segment(constraint_offset_[k], block.size()));
  }
}

// ============================================================================ iteration matrix

void MultibodySystem::assembleIterationMatrix(const ConstVec& q, const ConstVec& qdot,
                                              const ConstVec& lambda, double t,
                                              const IterationCoefficients& coeffs, SparseMatrix& h,
                                              double load_scale) const {
  assemble(q, qdot, lambda, t, coeffs, load_scale, nullptr, h);
}

void MultibodySystem::assembleForcesAndIterationMatrix(const ConstVec& q, const ConstVec& qdot,
                                                       const ConstVec& lambda, double t,
                                                       const IterationCoefficients& coeffs,
                                                       Eigen::VectorXd& f, SparseMatrix& h,
                                                       double load_scale) const {
  assemble(q, qdot, lambda, t, coeffs, load_scale, &f, h);
}

void MultibodySystem::assemble(const ConstVec& q, const ConstVec& qdot, const ConstVec& lambda,
                               double t, const IterationCoefficients& coeffs, double load_scale,
                               Eigen::VectorXd* f, SparseMatrix& h) const {
  requireFinalized("iteration matrix assembly");
  const int n = dofCount();
  MASTROM_ASSERT(q.size() == n && qdot.size() == n && lambda.size() == constraintCount());
  if (!hasPattern(h, h_pattern_)) h = h_pattern_;
  double* values = h.valuePtr();
  std::fill(values, values + h.nonZeros(), 0.0);
  if (f != nullptr) {
    f->resize(n);
    *f = load_scale * gravity_force_;
  }
  const double cm = coeffs.mass, cd = coeffs.damping, ck = coeffs.stiffness;
  const double sigma = coeffs.constraint_scale;

  // c_m M
  if (cm != 0.0) {
    const double* mv = mass_.valuePtr();
    for (size_t i = 0; i < mass_in_h_.size(); ++i) values[mass_in_h_[i]] += cm * mv[i];
  }

  // Elements: c_k (K_t + K_d) + c_d C_t in one pass over each element's points
  // (ShellElement::iterationTangent), and −F_elastic − F_damping. The tangents (70 % of an
  // assembly, which a step that renews its factorisation waits for) are formed on two threads
  // where allowed, each element whole on one, and added in element order: the same sums bit for
  // bit.
  const auto gatherElement = [&](size_t k, Vec36& e, Vec36& edot) {
    const auto& dofs = element_dofs_[k];
    for (int i = 0; i < 36; ++i) e[i] = q[dofs[static_cast<size_t>(i)]];
    if (element_damped_[k])
      for (int i = 0; i < 36; ++i) edot[i] = qdot[dofs[static_cast<size_t>(i)]];
    else
      edot.setZero();
  };
  const auto hasTangent = [&](size_t k) { return ck != 0.0 || (element_damped_[k] && cd != 0.0); };
  element_tangents_.resize(elements_.size());
  const auto formTangents = [&](size_t begin, size_t end) {
    Vec36 e, edot;
    for (size_t k = begin; k < end; ++k) {
      if (!hasTangent(k)) continue;
      gatherElement(k, e, edot);
      elements_[k].iterationTangent(e, edot, ck, element_damped_[k] ? cd : 0.0,
                                    element_tangents_[k]);
    }
  };
  const size_t half = elements_.size() / 2;
  runOnTwoThreads([&] { formTangents(0, half); }, [&] { formTangents(half, elements_.size()); },
                  threads_ > 1);
  Vec36 e, edot, fe, fd;
  for (size_t k = 0; k < elements_.size(); ++k) {
    const auto& dofs = element_dofs_[k];
    const bool damped = element_damped_[k];
    if (hasTangent(k)) {
      const std::vector<int>& pos = element_in_h_[k];
      const double* kv = element_tangents_[k].data();
      for (size_t i = 0; i < 36 * 36; ++i) values[pos[i]] += kv[i];
    }
    if (f != nullptr) {
      gatherElement(k, e, edot);
      elements_[k].elasticForce(e, fe);
      for (int i = 0; i < 36; ++i) (*f)[dofs[static_cast<size_t>(i)]] -= fe[i];
      if (damped) {
        elements_[k].dampingForce(e, edot, fd);
        for (int i = 0; i < 36; ++i) (*f)[dofs[static_cast<size_t>(i)]] -= fd[i];
      }
    }
  }

  // Constraints: σ Φ_q, σ Φ_qᵀ, c_k (Φ_qᵀλ)_q.
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    BlockScratch& s = block_scratch_[k];
    gather(block, q, s.q);
    block.jacobian(s.q, t, s.jac);
    const Scatter& sj = jac_in_h_[k];
    const Scatter& st = jact_in_h_[k];
    const double* jv = s.jac.data();
    for (size_t i = 0; i < sj.local.size(); ++i) {
      values[sj.position[i]] += sigma * jv[sj.local[i]];
      values[st.position[i]] += sigma * jv[st.local[i]];
    }
    if (ck != 0.0 && block.hasHessianTerm()) {
      s.lambda = lambda.segment(constraint_offset_[k], block.size());
      block.hessianTerm(s.q, s.lambda, t, s.hess);
      const Scatter& sh = hess_in_h_[k];
      const double* hv = s.hess.data();
      for (size_t i = 0; i < sh.local.size(); ++i) values[sh.position[i]] += ck * hv[sh.local[i]];
    }
  }

  // Applied loads: Q and −c_k s K_load.
  for (size_t k = 0; k < loads_.size(); ++k) {
    const AppliedLoad& load = *loads_[k];
    BlockScratch& s = load_scratch_[k];
    for (int i = 0; i < load.localDofCount(); ++i) s.q[i] = q[load.dofs()[static_cast<size_t>(i)]];
    if (f != nullptr) {
      load.force(s.q, t, s.out);
      for (int i = 0; i < load.localDofCount(); ++i)
        (*f)[load.dofs()[static_cast<size_t>(i)]] += load_scale * s.out[i];
    }
    if (ck != 0.0 && load.hasStiffness()) {
      load.stiffness(s.q, t, s.hess);
      const Scatter& sl = load_in_h_[k];
      const double* lv = s.hess.data();
      for (size_t i = 0; i < sl.local.size(); ++i)
        values[sl.position[i]] -= ck * load_scale * lv[sl.local[i]];
    }
  }
}

// ============================================================================ DaeSystem

void MultibodySystem::forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                             Eigen::VectorXd& q_force) {
  std::as_const(*this).forces(q, qdot, t, q_force, 1.0);
}

void MultibodySystem::constraints(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi) {
  std::as_const(*this).constraints(q, t, phi);
}

void MultibodySystem::evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                               Eigen::VectorXd& q_force, Eigen::VectorXd& phi, SparseMatrix& jac,
                               const std::function<void()>* side_work) {
  forcesAndConstraints(q, qdot, t, q_force, phi, jac, side_work);
}

void MultibodySystem::constraintJacobian(const Eigen::VectorXd& q, double t, SparseMatrix& jac) {
  std::as_const(*this).constraintJacobian(q, t, jac);
}

void MultibodySystem::velocityConstraintRhs(const Eigen::VectorXd& q, double t,
                                            Eigen::VectorXd& rhs) {
  constraintTimeDerivative(q, t, rhs);
  rhs = -rhs;
}

void MultibodySystem::accelerationConstraintRhs(const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& qdot, double t,
                                                Eigen::VectorXd& rhs) {
  Eigen::VectorXd phi_tt;
  constraintVelocityTerm(q, qdot, t, rhs);
  constraintSecondTimeDerivative(q, t, phi_tt);
  rhs = -(rhs + phi_tt);
}

void MultibodySystem::iterationMatrix(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                      const Eigen::VectorXd& lambda, double t,
                                      const IterationCoefficients& coeffs, SparseMatrix& h) {
  assembleIterationMatrix(q, qdot, lambda, t, coeffs, h, 1.0);
}

}  // namespace mastrom::fullorder
