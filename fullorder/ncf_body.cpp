// Rigid module in natural coordinates (docs/theory.md §2.1; [LW24] eqs. 1–7, [LW24] eq. 39).
//
// Everything here has the Kronecker structure (·) ⊗ I₃ over the four 3-blocks (r_i, r_j, u, v):
// a material point is r = aᵀ(X) ⊗ I₃ q with a = [1 − X/d, X/d, Y, Z], and each constraint is
// Φ_k = ½ qᵀ (H_k ⊗ I₃) q + const with a constant 4×4 H_k. The code works with the 4×4 pieces.
#include "fullorder/ncf_body.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstddef>

#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {

using Mat4 = Eigen::Matrix4d;
using Vec4 = Eigen::Vector4d;

// Block indices of q = [r_i; r_j; u; v].
constexpr int kRi = 0;
constexpr int kRj = 1;
constexpr int kU = 2;
constexpr int kV = 3;

/// K ⊗ I₃ for a 4×4 K.
Mat12 kronI3(const Mat4& k) {
  Mat12 out = Mat12::Zero();
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) out.block<3, 3>(3 * a, 3 * b).diagonal().setConstant(k(a, b));
  return out;
}

/// aᵀ ⊗ I₃ for a 4-vector a.
Mat3x12 rowKronI3(const Vec4& a) {
  Mat3x12 out = Mat3x12::Zero();
  for (int b = 0; b < 4; ++b) out.block<3, 3>(0, 3 * b).diagonal().setConstant(a(b));
  return out;
}

/// The constant 4×4 Hessians of the six constraints (header order), Φ_k = ½ qᵀ(H_k ⊗ I₃)q + c_k.
/// With w = r_j − r_i: w·w → 2(e_j − e_i)(e_j − e_i)ᵀ; u·u → 2e_u e_uᵀ; u·w → sym. (e_u, e_j −
/// e_i); …
std::array<Mat4, 6> constraintHessians() {
  Vec4 dw = Vec4::Zero();
  dw(kRi) = -1.0;
  dw(kRj) = 1.0;
  const Vec4 eu = Vec4::Unit(kU);
  const Vec4 ev = Vec4::Unit(kV);
  const auto sym = [](const Vec4& a, const Vec4& b) -> Mat4 {
    return a * b.transpose() + b * a.transpose();
  };
  return {sym(dw, dw), sym(eu, eu), sym(ev, ev), sym(eu, dw), sym(ev, dw), sym(eu, ev)};
}

}  // namespace

RigidModule::RigidModule(double axis_length_m, double mass_kg, const Eigen::Matrix3d& inertia_kg_m2)
    : d_(axis_length_m), m_(mass_kg), inertia_(inertia_kg_m2) {
  MASTROM_REQUIRE(std::isfinite(d_) && d_ > 0.0, InputError, "rigid module: axis length d = ", d_,
                  " m is out of range (must be finite and > 0)");
  MASTROM_REQUIRE(std::isfinite(m_) && m_ > 0.0, InputError, "rigid module: mass = ", m_,
                  " kg is out of range (must be finite and > 0)");
  MASTROM_REQUIRE(inertia_.allFinite(), InputError,
                  "rigid module: inertia tensor has a non-finite entry");
  const double scale = inertia_.cwiseAbs().maxCoeff();
  const double asym = (inertia_ - inertia_.transpose()).cwiseAbs().maxCoeff();
  MASTROM_REQUIRE(asym <= 1e-12 * scale, InputError,
                  "rigid module: inertia tensor is not symmetric (max |J - J^T| = ", asym,
                  " kg m^2, allowed <= 1e-12 * max |J| = ", 1e-12 * scale, ")");
  inertia_ = 0.5 * (inertia_ + inertia_.transpose()).eval();

  // Principal moments λ₁ ≤ λ₂ ≤ λ₃ must be positive and satisfy the strict triangle inequality
  // λ₁ + λ₂ > λ₃: that is exactly positive definiteness of the second-moment tensor S below, whose
  // eigenvalues are ½ tr J − λ_k — and so of the mass matrix. (Equality = a flat body, singular M.)
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia_, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d lam = eig.eigenvalues();
  MASTROM_REQUIRE(lam(0) > 0.0, InputError,
                  "rigid module: inertia tensor is not positive definite "
                  "(principal moments ",
                  lam(0), ", ", lam(1), ", ", lam(2), " kg m^2; all must be > 0)");
  MASTROM_REQUIRE(lam(0) + lam(1) - lam(2) > 1e-12 * lam(2), InputError,
                  "rigid module: principal moments ", lam(0), ", ", lam(1), ", ", lam(2),
                  " kg m^2 violate the triangle inequality (the two smallest must sum to more than "
                  "the largest)");

  // S_ab = ∫ρ X_a X_b dV = ½ tr(J) I − J (centroidal, so ∫ρ X dV = 0).
  const Eigen::Matrix3d s = 0.5 * inertia_.trace() * Eigen::Matrix3d::Identity() - inertia_;
  // N = ∫ρ a aᵀ dV with a = [1 − X/d, X/d, Y, Z]; M = N ⊗ I₃.
  const double d = d_;
  Mat4 n;
  n(kRi, kRi) = m_ + s(0, 0) / (d * d);
  n(kRi, kRj) = -s(0, 0) / (d * d);
  n(kRi, kU) = -s(0, 1) / d;
  n(kRi, kV) = -s(0, 2) / d;
  n(kRj, kRj) = s(0, 0) / (d * d);
  n(kRj, kU) = s(0, 1) / d;
  n(kRj, kV) = s(0, 2) / d;
  n(kU, kU) = s(1, 1);
  n(kU, kV) = s(1, 2);
  n(kV, kV) = s(2, 2);
  n.triangularView<Eigen::StrictlyLower>() = n.transpose();
  mass_matrix_ = kronI3(n);
}

Eigen::Matrix3d RigidModule::boxInertia(double mass_kg, double sx_m, double sy_m, double sz_m) {
  MASTROM_REQUIRE(std::isfinite(mass_kg) && mass_kg > 0.0, InputError,
                  "box inertia: mass = ", mass_kg, " kg is out of range (must be finite and > 0)");
  MASTROM_REQUIRE(std::isfinite(sx_m) && sx_m > 0.0 && std::isfinite(sy_m) && sy_m > 0.0 &&
                      std::isfinite(sz_m) && sz_m > 0.0,
                  InputError, "box inertia: sides (", sx_m, ", ", sy_m, ", ", sz_m,
                  ") m are out of range (each must be finite and > 0)");
  const double c = mass_kg / 12.0;
  return Eigen::Vector3d(c * (sy_m * sy_m + sz_m * sz_m), c * (sx_m * sx_m + sz_m * sz_m),
                         c * (sx_m * sx_m + sy_m * sy_m))
      .asDiagonal();
}

Vec12 RigidModule::coordinates(const Eigen::Vector3d& centroid_m,
                               const Eigen::Matrix3d& rotation) const {
  MASTROM_ASSERT((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm() < 1e-9);
  Vec12 q;
  q.segment<3>(3 * kRi) = centroid_m;
  q.segment<3>(3 * kRj) = centroid_m + d_ * rotation.col(0);
  q.segment<3>(3 * kU) = rotation.col(1);
  q.segment<3>(3 * kV) = rotation.col(2);
  return q;
}

Mat3x12 RigidModule::pointMap(const Eigen::Vector3d& local_m) const {
  const double xi = local_m.x() / d_;
  return rowKronI3(Vec4(1.0 - xi, xi, local_m.y(), local_m.z()));
}

Mat3x12 RigidModule::directionMap(const Eigen::Vector3d& local_direction) const {
  const double xi = local_direction.x() / d_;
  return rowKronI3(Vec4(-xi, xi, local_direction.y(), local_direction.z()));
}

Vec6 RigidModule::constraints(const Vec12& q) const {
  const Eigen::Vector3d w = q.segment<3>(3 * kRj) - q.segment<3>(3 * kRi);
  const Eigen::Vector3d u = q.segment<3>(3 * kU);
  const Eigen::Vector3d v = q.segment<3>(3 * kV);
  Vec6 phi;
  phi << w.dot(w) - d_ * d_, u.dot(u) - 1.0, v.dot(v) - 1.0, u.dot(w), v.dot(w), u.dot(v);
  return phi;
}

Mat6x12 RigidModule::constraintJacobian(const Vec12& q) const {
  const Eigen::Vector3d w = q.segment<3>(3 * kRj) - q.segment<3>(3 * kRi);
  const Eigen::Vector3d u = q.segment<3>(3 * kU);
  const Eigen::Vector3d v = q.segment<3>(3 * kV);
  Mat6x12 g = Mat6x12::Zero();
  // w·w − d²
  g.block<1, 3>(0, 3 * kRi) = -2.0 * w.transpose();
  g.block<1, 3>(0, 3 * kRj) = 2.0 * w.transpose();
  // u·u − 1, v·v − 1
  g.block<1, 3>(1, 3 * kU) = 2.0 * u.transpose();
  g.block<1, 3>(2, 3 * kV) = 2.0 * v.transpose();
  // u·w
  g.block<1, 3>(3, 3 * kRi) = -u.transpose();
  g.block<1, 3>(3, 3 * kRj) = u.transpose();
  g.block<1, 3>(3, 3 * kU) = w.transpose();
  // v·w
  g.block<1, 3>(4, 3 * kRi) = -v.transpose();
  g.block<1, 3>(4, 3 * kRj) = v.transpose();
  g.block<1, 3>(4, 3 * kV) = w.transpose();
  // u·v
  g.block<1, 3>(5, 3 * kU) = v.transpose();
  g.block<1, 3>(5, 3 * kV) = u.transpose();
  return g;
}

Mat12 RigidModule::constraintHessianTerm(const Vec6& lambda) const {
  static const std::array<Mat4, 6> hessians = constraintHessians();
  Mat4 sum = Mat4::Zero();
  for (int k = 0; k < kConstraints; ++k) sum += lambda(k) * hessians[static_cast<std::size_t>(k)];
  return kronI3(sum);
}

Vec6 RigidModule::constraintQuadraticVelocityTerm(const Vec12& qdot) const {
  // Φ_k quadratic ⇒ d²Φ_k/dt² = Φ_q q̈ + q̇ᵀ(H_k ⊗ I₃)q̇; the second part is returned.
  const Eigen::Vector3d wd = qdot.segment<3>(3 * kRj) - qdot.segment<3>(3 * kRi);
  const Eigen::Vector3d ud = qdot.segment<3>(3 * kU);
  const Eigen::Vector3d vd = qdot.segment<3>(3 * kV);
  Vec6 out;
  out << 2.0 * wd.dot(wd), 2.0 * ud.dot(ud), 2.0 * vd.dot(vd), 2.0 * ud.dot(wd), 2.0 * vd.dot(wd),
      2.0 * ud.dot(vd);
  return out;
}

Eigen::Matrix3d RigidModule::rotation(const Vec12& q) const {
  Eigen::Matrix3d r;
  r.col(0) = (q.segment<3>(3 * kRj) - q.segment<3>(3 * kRi)) / d_;
  r.col(1) = q.segment<3>(3 * kU);
  r.col(2) = q.segment<3>(3 * kV);
  return r;
}

Eigen::Vector3d RigidModule::angularVelocity(const Vec12& q, const Vec12& qdot) const {
  // For an orthonormal frame with ċ_k = ω × c_k: Σ c_k × (ω × c_k) = 3ω − Σ c_k (c_k·ω) = 2ω.
  const Eigen::Matrix3d c = rotation(q);
  const Eigen::Matrix3d cd = rotation(qdot);  // linear in q: the same map gives the frame rates
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) omega += c.col(k).cross(cd.col(k));
  return 0.5 * omega;
}

Eigen::Vector3d RigidModule::angularAcceleration(const Vec12& q, const Vec12& qddot) const {
  // d/dt of ½ Σ c_k × ċ_k: the ċ_k × ċ_k terms vanish, leaving ½ Σ c_k × c̈_k.
  return angularVelocity(q, qddot);
}

}  // namespace mastrom::fullorder
