// Finite-difference checks shared by the constraint, system and load tests.
//
// Steps follow the usual error balance (as MFEM's derivative tests do): a central first difference
// with step h has truncation error ~h²|f'''|/6 and round-off ~ε|f|/h, minimised near h = ∛ε ≈ 6e-6
// (relative to the variable's scale); a central second difference has ~h²|f''''|/12 + 4ε|f|/h²,
// minimised near h = ε^¼ ≈ 1e-4. The tolerances in the tests are a few times these estimates.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <random>

#include "fullorder/constraint.hpp"

namespace mastrom::fullorder::testing {

inline constexpr double kCbrtEps = 6.055454452393343e-06;  // ∛(2.2e-16)
inline constexpr double kQrtEps = 1.2207031250000000e-04;  // ε^¼

/// Central-difference Jacobian of a vector function f: R^n → R^m at x, step ∛ε · scale (scale = the
/// size of the variables).
inline Eigen::MatrixXd centralJacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
    double scale = 1.0) {
  const Eigen::VectorXd f0 = f(x);
  Eigen::MatrixXd jac(f0.size(), x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double h = kCbrtEps * scale;
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    jac.col(j) = (f(xp) - f(xm)) / (2.0 * h);
  }
  return jac;
}

inline Eigen::VectorXd evaluateBlock(const ConstraintBlock& b, const Eigen::VectorXd& q, double t) {
  Eigen::VectorXd phi(b.size());
  b.evaluate(q, t, phi);
  return phi;
}

inline Eigen::MatrixXd jacobianOf(const ConstraintBlock& b, const Eigen::VectorXd& q, double t) {
  Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(b.size(), b.localDofCount());
  b.jacobian(q, t, jac);
  return jac;
}

inline Eigen::MatrixXd hessianOf(const ConstraintBlock& b, const Eigen::VectorXd& q,
                                 const Eigen::VectorXd& lambda, double t) {
  Eigen::MatrixXd h(b.localDofCount(), b.localDofCount());
  b.hessianTerm(q, lambda, t, h);
  return h;
}

inline Eigen::VectorXd velocityTermOf(const ConstraintBlock& b, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd& qdot, double t) {
  Eigen::VectorXd g(b.size());
  b.velocityTerm(q, qdot, t, g);
  return g;
}

/// Every entry of `m` with |m_ij| > 0 is marked in `mask`.
inline bool insideStructure(const Eigen::MatrixXd& m, const BoolMatrix& mask) {
  if (m.rows() != mask.rows() || m.cols() != mask.cols()) return false;
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (m(i, j) != 0.0 && !mask(i, j)) return false;
  return true;
}

inline Eigen::Matrix3d randomRotationMatrix(std::mt19937& gen) {
  std::normal_distribution<double> nd;
  Eigen::Quaterniond q(nd(gen), nd(gen), nd(gen), nd(gen));
  q.normalize();
  return q.toRotationMatrix();
}

inline Eigen::VectorXd randomVector(std::mt19937& gen, Eigen::Index n, double scale) {
  std::uniform_real_distribution<double> ud(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = scale * ud(gen);
  return v;
}

}  // namespace mastrom::fullorder::testing
