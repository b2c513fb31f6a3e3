// The constrained equations of motion as the time integrator sees them (DESIGN §2.5):
//     M q̈ + Φ_qᵀ λ = Q(q, q̇, t),      Φ(q, t) = 0,
// with M constant. The integrator depends only on this interface; the mast assembly (and the
// small analytic systems of the tests) implement it.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace mastrom::fullorder {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// Coefficients of the iteration matrix
///   H = [ c_m M + c_d C_t + c_k K_t ,  s Φ_qᵀ ]
///       [ s Φ_q                     ,  0      ]
/// with C_t = −∂Q/∂q̇ and K_t = ∂(Φ_qᵀλ − Q)/∂q (including the constraint Hessian term).
struct IterationCoefficients {
  double mass = 1.0;
  double damping = 0.0;
  double stiffness = 0.0;
  double constraint_scale = 1.0;
};

class DaeSystem {
public:
  virtual ~DaeSystem() = default;

  virtual int dofCount() const = 0;
  virtual int constraintCount() const = 0;

  /// Constant mass matrix (n × n).
  virtual const SparseMatrix& massMatrix() const = 0;
  /// Q(q, q̇, t): applied minus internal (elastic + damping) generalized forces.
  virtual void forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                      Eigen::VectorXd& q_force) = 0;
  /// Φ(q, t).
  virtual void constraints(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi) = 0;
  /// Φ_q (m × n) with a pattern that never changes between calls.
  virtual void constraintJacobian(const Eigen::VectorXd& q, double t, SparseMatrix& jac) = 0;
  /// −Φ_t: right-hand side of the velocity constraint Φ_q q̇ = −Φ_t.
  virtual void velocityConstraintRhs(const Eigen::VectorXd& q, double t, Eigen::VectorXd& rhs) = 0;
  /// −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt: right-hand side of Φ_q q̈ = rhs (paper P-45/46).
  virtual void accelerationConstraintRhs(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                         double t, Eigen::VectorXd& rhs) = 0;
  /// The (n + m) square iteration matrix H above; its sparsity pattern must not change between calls
  /// (the integrator analyses it once).
  virtual void iterationMatrix(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                               const Eigen::VectorXd& lambda, double t,
                               const IterationCoefficients& coeffs, SparseMatrix& h) = 0;
};

}  // namespace mastrom::fullorder
