// The constrained equations of motion as the time integrator sees them (docs/theory.md §5):
//     M q̈ + Φ_qᵀ λ = Q(q, q̇, t),      Φ(q, t) = 0,
// with M constant. The integrator depends only on this interface; the mast assembly (and the
// small analytic systems of the tests) implement it.
#pragma once

#include <cmath>
#include <exception>
#include <functional>
#include <vector>

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

/// A rigid rotation about the global Z axis under which a system's iteration matrix is equivariant
/// (DaeSystem::rotationSymmetry()). It acts on (n + m) vectors [primal; multipliers]: the x, y
/// components of every listed Cartesian 3-vector turn by δ, everything else is invariant.
struct RotationSymmetry {
  /// Index of the x component of every rotating 3-vector in [primal; multipliers].
  std::vector<int> triple_starts;

  /// x ← P_δ x.
  void rotate(double delta_rad, Eigen::Ref<Eigen::VectorXd> x) const {
    const double c = std::cos(delta_rad), s = std::sin(delta_rad);
    double* v = x.data();
    for (int i : triple_starts) {
      const double a = v[i], b = v[i + 1];
      v[i] = c * a - s * b;
      v[i + 1] = s * a + c * b;
    }
  }
};

/// Runs the two halves of DaeSystem::evaluatePairOn(): the first on the calling thread, the second
/// on another thread if one takes it while the first runs (fullorder/work_offer.hpp).
class PairRunner {
public:
  virtual ~PairRunner() = default;
  /// Whether another thread waits for work now (an offer made otherwise would only cost).
  virtual bool secondThreadFree() const = 0;
  /// Run `first` here and offer `second`; true when `second` ran (to completion), false when
  /// nobody took it before `first` was done (it then does not run at all).
  virtual bool run(const std::function<void()>& first, const std::function<void()>& second) = 0;
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
  /// Q, Φ and Φ_q at one state — what every Newton iteration asks for. Default: the three calls; a
  /// system may overlap them (MultibodySystem: the constraints on one thread while the element
  /// forces run on the others). The values must equal those of the three calls. `side_work`, when
  /// given, runs on the calling thread before q_force, phi or jac is written; it must not call this
  /// system (other threads may be using its buffers meanwhile).
  virtual void evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                        Eigen::VectorXd& q_force, Eigen::VectorXd& phi, SparseMatrix& jac,
                        const std::function<void()>* side_work = nullptr) {
    if (side_work != nullptr) (*side_work)();
    forces(q, qdot, t, q_force);
    constraints(q, t, phi);
    constraintJacobian(q, t, jac);
  }
  /// The inputs and outputs of one evaluate() call.
  struct Evaluation {
    const Eigen::VectorXd* q;
    const Eigen::VectorXd* qdot;
    double t;
    Eigen::VectorXd* q_force;
    Eigen::VectorXd* phi;
    SparseMatrix* jac;
    /// Optional: run on the same thread right after this evaluation succeeded (it may read its
    /// outputs; it must not call the system).
    const std::function<void()>* then = nullptr;
  };
  /// Whether evaluatePair() runs its two evaluations at once (on two threads).
  virtual bool evaluatesPairs() const { return false; }
  /// Two evaluate() calls — on two threads at once where evaluatesPairs() — each with the values
  /// evaluate() gives, bit for bit. An exception of the first is thrown; one of the second only
  /// makes the function return false (its outputs are then unspecified): the pipelined time step
  /// evaluates the next step's predictor speculatively, and a failure there belongs to that step.
  virtual bool evaluatePair(const Evaluation& first, const Evaluation& second) {
    evaluate(*first.q, *first.qdot, first.t, *first.q_force, *first.phi, *first.jac);
    if (first.then != nullptr) (*first.then)();
    try {
      evaluate(*second.q, *second.qdot, second.t, *second.q_force, *second.phi, *second.jac);
      if (second.then != nullptr) (*second.then)();
    } catch (...) {
      return false;
    }
    return true;
  }
  /// Whether evaluatePairOn() can hand its second evaluation to another thread.
  virtual bool evaluatesPairsOn() const { return false; }
  /// evaluatePair() with the second evaluation offered through `runner` (a thread that has
  /// finished other work takes it, GeneralizedAlpha::setPairRunner): the first always runs (its
  /// exception is thrown); true when the second ran and succeeded. Default: the first alone.
  virtual bool evaluatePairOn(PairRunner& runner, const Evaluation& first,
                              const Evaluation& second) {
    (void)runner;
    (void)second;
    evaluate(*first.q, *first.qdot, first.t, *first.q_force, *first.phi, *first.jac);
    if (first.then != nullptr) (*first.then)();
    return false;
  }
  /// −Φ_t: right-hand side of the velocity constraint Φ_q q̇ = −Φ_t.
  virtual void velocityConstraintRhs(const Eigen::VectorXd& q, double t, Eigen::VectorXd& rhs) = 0;
  /// −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt: right-hand side of Φ_q q̈ = rhs ([LW24] eq. 45/46).
  virtual void accelerationConstraintRhs(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                         double t, Eigen::VectorXd& rhs) = 0;
  /// The (n + m) square iteration matrix H above; its sparsity pattern must not change between calls
  /// (the integrator analyses it once).
  virtual void iterationMatrix(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                               const Eigen::VectorXd& lambda, double t,
                               const IterationCoefficients& coeffs, SparseMatrix& h) = 0;

  /// Optional symmetry, for reusing factorisations while the system turns. When not
  /// null: for every state (q, q̇, λ, t) and time t′, with δ = rotationAngle(t′) − rotationAngle(t),
  ///   H(R_δ q, R_δ q̇, P_δ λ, t′) = P_δ H(q, q̇, λ, t) P_δᵀ      (P_δ = rotationSymmetry()->rotate(δ))
  /// where R_δ turns every body and node about Z. Then H(now)⁻¹ ≈ P_δ H(then)⁻¹ P_δᵀ to within the
  /// change of the elastic state alone, however far the system has turned. Default: none.
  virtual const RotationSymmetry* rotationSymmetry() const { return nullptr; }
  /// The angle [rad] the symmetric frame has turned by at time t (the drive angle of the mast).
  virtual double rotationAngle(double t) const {
    (void)t;
    return 0.0;
  }
};

}  // namespace mastrom::fullorder
