// Constraint blocks: the pieces Φ(q, t) = 0 of the multibody system is assembled from
// (docs/theory.md §2.1, §2.3 – §2.5; [LW24] eqs. 39–46).
//
// A block owns `size()` equations that touch a fixed list of global DOFs, `dofs()`. Every method
// works on the *local* vectors gathered from those DOFs (q_local[k] = q[dofs()[k]]); the system
// scatters the results. Conventions, used by the whole of fullorder/:
//   equations of motion   M q̈ + Φ_qᵀ λ = Q(q, q̇, t),   Φ(q, t) = 0,
// so the constraint (reaction) force on the system is −Φ_qᵀλ. A block reports
//   Φ                                     evaluate()
//   Φ_q (size × local DOFs, dense)        jacobian()
//   (Φ_qᵀλ)_q (local × local, symmetric)  hessianTerm()    — only if hasHessianTerm()
//   Φ_t, Φ_tt                             timeDerivative(), secondTimeDerivative() — zero unless
//                                         isTimeDependent() (driving constraints)
//   γ_v = (Φ_q q̇)_q q̇ + 2 Φ_qt q̇         velocityTerm()
// so that the time derivatives of Φ = 0 along a motion read
//   Φ_q q̇ = −Φ_t,    Φ_q q̈ = −(γ_v + Φ_tt)        (the index-1 rows of [LW24] eq. 45).
// jacobianStructure()/hessianStructure() mark the entries that can ever be non-zero; the system
// builds its sparsity pattern from them once (entries outside are never written).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mastrom::fullorder {

using BoolMatrix = Eigen::Matrix<bool, Eigen::Dynamic, Eigen::Dynamic>;

class ConstraintBlock {
public:
  using ConstVec = Eigen::Ref<const Eigen::VectorXd>;

  virtual ~ConstraintBlock() = default;

  /// Number of equations.
  int size() const { return size_; }
  /// Global DOF indices touched, in local order.
  const std::vector<int>& dofs() const { return dofs_; }
  int localDofCount() const { return static_cast<int>(dofs_.size()); }
  /// Short human-readable description (diagnostics and error messages).
  virtual std::string name() const = 0;

  /// Φ(q, t) ∈ R^size.
  virtual void evaluate(const ConstVec& q, double t, Eigen::Ref<Eigen::VectorXd> phi) const = 0;
  /// Φ_q (size × localDofCount()): every entry of jacobianStructure() is overwritten; a block may
  /// leave the others untouched, so callers pass a matrix that is zero there (the system zeroes
  /// its scratch once — rewriting the zeros of the mast's 48 bonded-edge blocks on every call was
  /// 2 % of a time step).
  virtual void jacobian(const ConstVec& q, double t, Eigen::Ref<Eigen::MatrixXd> jac) const = 0;

  /// False when Φ is linear in q (the Hessian term vanishes and assembly skips it).
  virtual bool hasHessianTerm() const = 0;
  /// (Φ_qᵀλ)_q (localDofCount² , symmetric), overwritten. Default: zero.
  virtual void hessianTerm(const ConstVec& q, const ConstVec& lambda, double t,
                           Eigen::Ref<Eigen::MatrixXd> h) const {
    (void)q, (void)lambda, (void)t;
    h.setZero();
  }

  /// True for driving (rheonomic) constraints.
  virtual bool isTimeDependent() const { return false; }
  /// ∂Φ/∂t, overwritten. Default: zero.
  virtual void timeDerivative(const ConstVec& q, double t,
                              Eigen::Ref<Eigen::VectorXd> phi_t) const {
    (void)q, (void)t;
    phi_t.setZero();
  }
  /// ∂²Φ/∂t², overwritten. Default: zero.
  virtual void secondTimeDerivative(const ConstVec& q, double t,
                                    Eigen::Ref<Eigen::VectorXd> phi_tt) const {
    (void)q, (void)t;
    phi_tt.setZero();
  }
  /// γ_v = (Φ_q q̇)_q q̇ + 2 Φ_qt q̇, overwritten.
  virtual void velocityTerm(const ConstVec& q, const ConstVec& qdot, double t,
                            Eigen::Ref<Eigen::VectorXd> gamma) const = 0;

  /// Rigid-rotation symmetry (DaeSystem::rotationSymmetry()). Turn every body and node about the
  /// global Z axis through the origin by δ and advance t so that frameAngle(t) grows by δ: if every
  /// row of Φ is then unchanged, except rows forming Cartesian 3-vectors which turn by δ too, return
  /// the first row of every such triple. Default: nullopt — the block breaks the symmetry (or does
  /// not say), and the system does without it.
  virtual std::optional<std::vector<int>> rotatingRowTriples() const { return std::nullopt; }
  /// For a time-dependent block: the angle [rad] by which its equations have turned at time t.
  virtual double frameAngle(double t) const {
    (void)t;
    return 0.0;
  }

  /// Entries of Φ_q that may be non-zero. Default: all.
  virtual BoolMatrix jacobianStructure() const {
    return BoolMatrix::Constant(size_, localDofCount(), true);
  }
  /// Entries of (Φ_qᵀλ)_q that may be non-zero. Default: all if hasHessianTerm(), else none.
  virtual BoolMatrix hessianStructure() const {
    return BoolMatrix::Constant(localDofCount(), localDofCount(), hasHessianTerm());
  }

protected:
  ConstraintBlock(int size, std::vector<int> dofs) : size_(size), dofs_(std::move(dofs)) {}

private:
  int size_;
  std::vector<int> dofs_;
};

}  // namespace mastrom::fullorder
