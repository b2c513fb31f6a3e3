// Tests of the rigid module in natural coordinates (docs/theory.md §2.1; [LW24] eqs. 1–7, [LW24]
// eq. 39).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "common/error.hpp"
#include "fullorder/ncf_body.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

Eigen::Vector3d randomVector(std::mt19937& rng, double scale = 1.0) {
  std::normal_distribution<double> normal(0.0, scale);
  return {normal(rng), normal(rng), normal(rng)};
}

Vec12 randomVec12(std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Vec12 q;
  for (int i = 0; i < 12; ++i) q(i) = normal(rng);
  return q;
}

/// Uniformly distributed rotation (normalised Gaussian quaternion).
Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Quaterniond quat(normal(rng), normal(rng), normal(rng), normal(rng));
  quat.normalize();
  return quat.toRotationMatrix();
}

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d s;
  s << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return s;
}

/// exp(s [w]×), by Rodrigues through AngleAxis.
Eigen::Matrix3d expSkew(const Eigen::Vector3d& w, double s) {
  const double n = w.norm();
  if (n == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(s * n, w / n).toRotationMatrix();
}

/// Stacks a body with centroid c and frame R (and their rates) into NCF coordinates, written out
/// here independently of RigidModule::coordinates: [c; c + d R e₁; R e₂; R e₃].
Vec12 stackFrame(double d, const Eigen::Vector3d& c, const Eigen::Matrix3d& r) {
  Vec12 q;
  q << c, c + d * r.col(0), r.col(1), r.col(2);
  return q;
}

/// The cube module of docs/theory.md §1 defaults.
RigidModule cubeModule() {
  return RigidModule(0.10, 0.50, RigidModule::boxInertia(0.50, 0.10, 0.10, 0.10));
}

/// A box of sides `sides` whose edges are turned by `box_frame` against the module's axes, so the
/// inertia in the module frame is full: J = Q J_box Qᵀ.
struct TiltedBox {
  double mass = 0.7;
  Eigen::Vector3d sides{0.10, 0.14, 0.07};
  Eigen::Matrix3d box_frame;
  Eigen::Matrix3d inertia() const {
    return box_frame * RigidModule::boxInertia(mass, sides.x(), sides.y(), sides.z()) *
           box_frame.transpose();
  }
};

TiltedBox tiltedBox() {
  std::mt19937 rng(7);
  return TiltedBox{0.7, {0.10, 0.14, 0.07}, randomRotation(rng)};
}

RigidModule tiltedModule() {
  const TiltedBox box = tiltedBox();
  return RigidModule(0.12, box.mass, box.inertia());
}

/// ∫ρ AᵀA dV for a uniform box by 2×2×2 Gauss quadrature. A(X) is affine in X, so AᵀA is quadratic
/// in each box coordinate and 2-point Gauss is exact. A is built here independently of pointMap.
Mat12 quadratureMassMatrix(double d, const TiltedBox& box) {
  const double rho = box.mass / box.sides.prod();
  const double g = 1.0 / std::sqrt(3.0);
  Mat12 m = Mat12::Zero();
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d xi((i & 1) ? g : -g, (i & 2) ? g : -g, (i & 4) ? g : -g);
    const Eigen::Vector3d x = box.box_frame * (0.5 * box.sides.cwiseProduct(xi));
    Mat3x12 a;
    a << (1.0 - x.x() / d) * Eigen::Matrix3d::Identity(), (x.x() / d) * Eigen::Matrix3d::Identity(),
        x.y() * Eigen::Matrix3d::Identity(), x.z() * Eigen::Matrix3d::Identity();
    const double weight = rho * box.sides.prod() / 8.0;  // Jacobian V/8, unit Gauss weights
    m.noalias() += weight * a.transpose() * a;
  }
  return m;
}

// ---------------------------------------------------------------------------------------------
TEST(RigidModule, MassMatrixSymmetricPositiveDefinite) {
  for (const RigidModule& body : {cubeModule(), tiltedModule()}) {
    const Mat12& m = body.massMatrix();
    EXPECT_EQ((m - m.transpose()).cwiseAbs().maxCoeff(), 0.0);
    const Eigen::SelfAdjointEigenSolver<Mat12> eig(m, Eigen::EigenvaluesOnly);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 1e-8 * eig.eigenvalues().maxCoeff());
    EXPECT_EQ(Eigen::LLT<Mat12>(m).info(), Eigen::Success);
  }
}

TEST(RigidModule, MassMatrixEqualsVolumeQuadratureOfTiltedBox) {
  // Independent reference: integrate ρAᵀA over the actual (tilted) box.
  const TiltedBox box = tiltedBox();
  const RigidModule body(0.12, box.mass, box.inertia());
  const Mat12 reference = quadratureMassMatrix(0.12, box);
  EXPECT_LE((body.massMatrix() - reference).cwiseAbs().maxCoeff(),
            1e-13 * reference.cwiseAbs().maxCoeff());
  // The inertia really is non-diagonal, so the off-diagonal blocks of M are exercised.
  EXPECT_GT(std::abs(box.inertia()(0, 1)), 1e-2 * box.inertia().trace());
}

TEST(RigidModule, KineticEnergyOfRandomRigidMotions) {
  // ½ q̇ᵀMq̇ = ½ m|v|² + ½ ωᵀ(R J Rᵀ)ω with ṙ = v + ω × (r − c) at r_i = c and r_j, u̇ = ω × u, …
  std::mt19937 rng(20240117);
  for (const RigidModule& body : {cubeModule(), tiltedModule()}) {
    const double d = body.axisLength();
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::Matrix3d r = randomRotation(rng);
      const Eigen::Vector3d c = randomVector(rng, 2.0);
      const Eigen::Vector3d omega = randomVector(rng, 3.0);
      const Eigen::Vector3d v = randomVector(rng, 0.5);
      Vec12 qdot;
      qdot << v, v + omega.cross(d * r.col(0)), omega.cross(r.col(1)), omega.cross(r.col(2));
      const double t_ncf = 0.5 * qdot.dot(body.massMatrix() * qdot);
      const Eigen::Matrix3d j_global = r * body.inertia() * r.transpose();
      const double t_ref = 0.5 * body.mass() * v.squaredNorm() + 0.5 * omega.dot(j_global * omega);
      EXPECT_NEAR(t_ncf, t_ref, 1e-12 * t_ref) << "trial " << trial;
      // The stacked coordinates agree with the class's own constructor from (c, R).
      EXPECT_LE((body.coordinates(c, r) - stackFrame(d, c, r)).cwiseAbs().maxCoeff(),
                1e-15 * (1 + c.norm()));
    }
  }
}

TEST(RigidModule, ConstraintsVanishOnRigidPlacements) {
  std::mt19937 rng(11);
  for (const RigidModule& body : {cubeModule(), tiltedModule()}) {
    const double d = body.axisLength();
    for (int trial = 0; trial < 100; ++trial) {
      const Eigen::Matrix3d r = randomRotation(rng);
      const Eigen::Vector3d c = randomVector(rng, 10.0);
      const Vec12 q = body.coordinates(c, r);
      const Vec6 phi = body.constraints(q);
      // Rounding of r_j − r_i is ~ε|c| absolute, i.e. ε|c|/d relative to d; scale each row by its
      // natural size (d² for w·w, d for u·w and v·w, 1 for the unit vectors).
      const double rel = 64.0 * kEps * (1.0 + c.norm() / d);
      Vec6 scale;
      scale << d * d, 1.0, 1.0, d, d, 1.0;
      for (int k = 0; k < 6; ++k) EXPECT_NEAR(phi(k), 0.0, rel * scale(k)) << "row " << k;
      EXPECT_LE((body.rotation(q) - r).cwiseAbs().maxCoeff(), rel);
    }
  }
}

// Φ is quadratic in q, so the central difference has zero truncation error (Φ‴ ≡ 0) and only
// rounding remains: e_Φ/h with e_Φ ≈ 16ε(2‖q‖∞ + h)² for the few products and sums of one row.
// A large step h = 1e-2 therefore gives the tightest test; the tolerance is 2e_Φ/h.
TEST(RigidModule, JacobianMatchesCentralDifferences) {
  std::mt19937 rng(3);
  const RigidModule body = tiltedModule();
  const double h = 1e-2;
  for (int trial = 0; trial < 20; ++trial) {
    const Vec12 q = randomVec12(rng);  // off the manifold on purpose: Φ_q holds everywhere
    const Mat6x12 jac = body.constraintJacobian(q);
    const double size = 2.0 * q.cwiseAbs().maxCoeff() + h + body.axisLength();
    const double tol = 2.0 * 16.0 * kEps * size * size / h;
    for (int j = 0; j < 12; ++j) {
      Vec12 qp = q;
      Vec12 qm = q;
      qp(j) += h;
      qm(j) -= h;
      const Vec6 fd = (body.constraints(qp) - body.constraints(qm)) / (qp(j) - qm(j));
      for (int k = 0; k < 6; ++k) EXPECT_NEAR(jac(k, j), fd(k), tol) << "Φ" << k << " / q" << j;
    }
  }
}

// g(q) = Φ_q(q)ᵀλ is linear in q, so again the central difference is exact up to rounding.
TEST(RigidModule, HessianTermMatchesDifferencesOfJacobianTransposeTimesLambda) {
  std::mt19937 rng(5);
  const RigidModule body = tiltedModule();
  const double h = 1e-2;
  for (int trial = 0; trial < 10; ++trial) {
    const Vec12 q = randomVec12(rng);
    const Vec6 lambda = randomVec12(rng).head<6>();
    const Mat12 hess = body.constraintHessianTerm(lambda);
    EXPECT_EQ((hess - hess.transpose()).cwiseAbs().maxCoeff(), 0.0);
    const double size = (2.0 * q.cwiseAbs().maxCoeff() + h) * lambda.cwiseAbs().sum();
    const double tol = 2.0 * 16.0 * kEps * size / h;
    for (int j = 0; j < 12; ++j) {
      Vec12 qp = q;
      Vec12 qm = q;
      qp(j) += h;
      qm(j) -= h;
      const Vec12 gp = body.constraintJacobian(qp).transpose() * lambda;
      const Vec12 gm = body.constraintJacobian(qm).transpose() * lambda;
      const Vec12 fd = (gp - gm) / (qp(j) - qm(j));
      for (int i = 0; i < 12; ++i)
        EXPECT_NEAR(hess(i, j), fd(i), tol) << "(" << i << ", " << j << ")";
    }
  }
}

// Along q(t) = q₀ + t q₁ + ½t² q₂ the constraint Φ(q(t)) is a quartic polynomial in t, so the
// second central difference D(h) = [Φ(h) − 2Φ(0) + Φ(−h)]/h² = Φ̈(0) + h²/12 Φ⁗ holds *exactly*
// (no higher terms). One Richardson step, [4D(h) − D(2h)]/3, removes the h² term and leaves only
// rounding, ≈ (16 + 1)/3 · 4e_Φ/h²; so a large h = 0.1 is best. Then d²Φ/dt²(0) = Φ_q(q₀) q₂ +
// γ(q₁).
TEST(RigidModule, QuadraticVelocityTermIsSecondTimeDerivativeOfConstraints) {
  std::mt19937 rng(9);
  const RigidModule body = tiltedModule();
  const double h = 0.1;
  for (int trial = 0; trial < 20; ++trial) {
    const Vec12 q0 = randomVec12(rng);
    const Vec12 q1 = randomVec12(rng);
    const Vec12 q2 = randomVec12(rng);
    const auto phi_at = [&](double t) -> Vec6 {
      const Vec12 q = q0 + t * q1 + 0.5 * t * t * q2;
      return body.constraints(q);
    };
    const auto second_difference = [&](double step) -> Vec6 {
      return (phi_at(step) - 2.0 * phi_at(0.0) + phi_at(-step)) / (step * step);
    };
    const Vec6 phi_ddot = (4.0 * second_difference(h) - second_difference(2.0 * h)) / 3.0;
    const Vec6 gamma = body.constraintQuadraticVelocityTerm(q1);
    const Vec6 expected = phi_ddot - body.constraintJacobian(q0) * q2;
    const double size = 2.0 * (q0.cwiseAbs().maxCoeff() + 2.0 * h * q1.cwiseAbs().maxCoeff() +
                               2.0 * h * h * q2.cwiseAbs().maxCoeff()) +
                        body.axisLength();
    const double e_phi = 16.0 * kEps * size * size;
    const double tol = 2.0 * (17.0 / 3.0) * 4.0 * e_phi / (h * h);
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(gamma(k), expected(k), tol) << "row " << k;
  }
}

TEST(RigidModule, AccelerationLevelConstraintsHoldForRigidMotion) {
  // On a rigid motion Φ ≡ 0, hence Φ_q q̈ + γ(q̇) = 0 with the rigid-body q̈.
  std::mt19937 rng(13);
  const RigidModule body = cubeModule();
  const double d = body.axisLength();
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d r = randomRotation(rng);
    const Eigen::Vector3d c = randomVector(rng);
    const Eigen::Vector3d w = randomVector(rng, 2.0);
    const Eigen::Vector3d alpha = randomVector(rng, 5.0);
    const Eigen::Vector3d vel = randomVector(rng);
    const Eigen::Vector3d acc = randomVector(rng);
    const Vec12 q = body.coordinates(c, r);
    const Eigen::Matrix3d rdot = skew(w) * r;
    const Eigen::Matrix3d rddot = (skew(alpha) + skew(w) * skew(w)) * r;
    const Vec12 qdot = stackFrame(d, vel, rdot);
    const Vec12 qddot = stackFrame(d, acc, rddot);
    const Vec6 residual =
        body.constraintJacobian(q) * qddot + body.constraintQuadraticVelocityTerm(qdot);
    EXPECT_LE(residual.cwiseAbs().maxCoeff(),
              1e-13 * (1.0 + alpha.squaredNorm() + w.squaredNorm()));
  }
}

// Prescribed rotation R(t) = exp(t[w]×) exp(½t²[w2]×) = R₁R₂. Then ṘRᵀ = [w + t R₁w2]×, so
//   ω(t) = w + t R₁ w2,   α(t) = ω̇ = R₁ w2 + t w × (R₁ w2),
// and Ṙ, R̈ follow from the product rule (written out below, not via ω).
struct PrescribedMotion {
  Eigen::Vector3d w, w2, c0, v0;
  double d;

  Eigen::Matrix3d r1(double t) const { return expSkew(w, t); }
  Eigen::Matrix3d r2(double t) const { return expSkew(w2, 0.5 * t * t); }
  Vec12 q(double t) const { return stackFrame(d, c0 + t * v0, r1(t) * r2(t)); }
  Vec12 qdot(double t) const {
    const Eigen::Matrix3d rdot = skew(w) * r1(t) * r2(t) + r1(t) * (t * skew(w2)) * r2(t);
    return stackFrame(d, v0, rdot);
  }
  Vec12 qddot(double t) const {
    const Eigen::Matrix3d a = skew(w);
    const Eigen::Matrix3d b = skew(w2);
    const Eigen::Matrix3d rddot = a * a * r1(t) * r2(t) + 2.0 * t * a * r1(t) * b * r2(t) +
                                  r1(t) * (b + t * t * b * b) * r2(t);
    return stackFrame(d, Eigen::Vector3d::Zero(), rddot);
  }
  Eigen::Vector3d omega(double t) const { return w + t * r1(t) * w2; }
  Eigen::Vector3d alpha(double t) const {
    const Eigen::Vector3d rw2 = r1(t) * w2;
    return rw2 + t * w.cross(rw2);
  }
};

TEST(RigidModule, AngularVelocityAndAccelerationOfPrescribedRotation) {
  std::mt19937 rng(17);
  const RigidModule body = tiltedModule();
  for (int trial = 0; trial < 10; ++trial) {
    const PrescribedMotion motion{randomVector(rng), randomVector(rng), randomVector(rng),
                                  randomVector(rng), body.axisLength()};
    const auto omega_of = [&](double t) -> Eigen::Vector3d {
      return body.angularVelocity(motion.q(t), motion.qdot(t));
    };
    for (double t : {0.0, 0.3, 0.7, 1.2}) {
      const double scale = motion.w.norm() + (1.0 + 2.0 * t) * motion.w2.norm();
      const Eigen::Vector3d omega = omega_of(t);
      const Eigen::Vector3d alpha = body.angularAcceleration(motion.q(t), motion.qddot(t));
      EXPECT_LE((omega - motion.omega(t)).norm(), 1e-13 * scale) << "t = " << t;
      EXPECT_LE((alpha - motion.alpha(t)).norm(), 1e-13 * scale * scale) << "t = " << t;

      // α against central differences of the class's own ω(t), step ∛ε. The truncation error of
      // D(h) is c h² + O(h⁴), so |D(2h) − D(h)| ≈ 3|c|h² estimates it from the data; the rounding
      // part is ≈ 16ε|ω|/h.
      const double h = std::cbrt(kEps);
      const auto central = [&](double step) -> Eigen::Vector3d {
        return (omega_of(t + step) - omega_of(t - step)) / (2.0 * step);
      };
      const Eigen::Vector3d d1 = central(h);
      const Eigen::Vector3d d2 = central(2.0 * h);
      const double tol = (d2 - d1).norm() + 2.0 * 16.0 * kEps * scale / h;
      EXPECT_LE((alpha - d1).norm(), tol) << "t = " << t;
    }
  }
}

TEST(RigidModule, PointAndDirectionMapsReproduceMaterialPoints) {
  std::mt19937 rng(19);
  const RigidModule body = tiltedModule();
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d r = randomRotation(rng);
    const Eigen::Vector3d c = randomVector(rng);
    const Vec12 q = body.coordinates(c, r);
    const Eigen::Vector3d x = randomVector(rng, 0.1);
    const Eigen::Vector3d expected = c + r * x;
    EXPECT_LE((body.pointMap(x) * q - expected).norm(), 1e-14 * (1.0 + c.norm())) << trial;
    EXPECT_LE((body.directionMap(x) * q - r * x).norm(),
              1e-14 * (1.0 + c.norm() / body.axisLength()) * x.norm())
        << trial;
  }
  // The two reference points themselves.
  const Vec12 q = body.coordinates(Eigen::Vector3d(1, 2, 3), Eigen::Matrix3d::Identity());
  EXPECT_LE((body.pointMap(Eigen::Vector3d::Zero()) * q - Eigen::Vector3d(1, 2, 3)).norm(), 1e-15);
  EXPECT_LE((body.pointMap(Eigen::Vector3d(body.axisLength(), 0, 0)) * q - q.segment<3>(3)).norm(),
            1e-15);
}

// ---------------------------------------------------------------------------------------------
void expectRejected(double d, double m, const Eigen::Matrix3d& j, const std::string& what) {
  try {
    const RigidModule body(d, m, j);
    static_cast<void>(body);
    ADD_FAILURE() << "accepted: " << what;
  } catch (const InputError& e) {
    EXPECT_FALSE(std::string(e.what()).empty());
  }
}

TEST(RigidModule, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Eigen::Matrix3d good = RigidModule::boxInertia(0.5, 0.1, 0.1, 0.1);
  for (double bad : {0.0, -0.1, nan, inf}) {
    expectRejected(bad, 0.5, good, "axis length " + std::to_string(bad));
    expectRejected(0.1, bad, good, "mass " + std::to_string(bad));
  }
  Eigen::Matrix3d asym = good;
  asym(0, 1) = 1e-4;
  expectRejected(0.1, 0.5, asym, "non-symmetric inertia");
  Eigen::Matrix3d with_nan = good;
  with_nan(2, 2) = nan;
  expectRejected(0.1, 0.5, with_nan, "NaN inertia");
  expectRejected(0.1, 0.5, -good, "negative definite inertia");
  expectRejected(0.1, 0.5, Eigen::Vector3d(1e-3, 1e-3, 3e-3).asDiagonal(), "triangle inequality");
  expectRejected(0.1, 0.5, Eigen::Vector3d(1e-3, 1e-3, 2e-3).asDiagonal(), "flat plate (equality)");
  // The same violation hidden in a full tensor.
  std::mt19937 rng(23);
  const Eigen::Matrix3d rot = randomRotation(rng);
  const Eigen::Matrix3d bad_full =
      rot * Eigen::Vector3d(1e-3, 1.5e-3, 3e-3).asDiagonal() * rot.transpose();
  expectRejected(0.1, 0.5, 0.5 * (bad_full + bad_full.transpose()), "rotated triangle violation");
  // A tilted, genuinely full tensor is accepted.
  EXPECT_NO_THROW(tiltedModule());

  EXPECT_THROW(RigidModule::boxInertia(0.0, 0.1, 0.1, 0.1), InputError);
  EXPECT_THROW(RigidModule::boxInertia(0.5, 0.1, -0.1, 0.1), InputError);
  EXPECT_THROW(RigidModule::boxInertia(0.5, 0.1, 0.1, nan), InputError);
}

}  // namespace
}  // namespace mastrom::fullorder
