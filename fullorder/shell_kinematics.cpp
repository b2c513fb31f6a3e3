#include "fullorder/shell_kinematics.hpp"

#include <cmath>

#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {

inline Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d s;
  s << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return s;
}

/// v = P w / l for the unit normal n (projection of w onto the tangent plane, divided by l).
inline Eigen::Vector3d tangentialPart(const ShellPointKinematics& kin, const Eigen::Vector3d& w) {
  return (w - kin.n * kin.n.dot(w)) / kin.area_factor;
}

/// vec(x yᵀ) of a 3-vector and a 12-vector, as a 36-row (column-major = e ordering).
inline void addOuter(const Eigen::Vector3d& x, const Vec12& y, Mat6x36& b, int row) {
  for (int k = 0; k < 12; ++k) b.block<1, 3>(row, 3 * k) += y[k] * x.transpose();
}

}  // namespace

// T maps covariant parameter-coordinate strains (Voigt, 2E₁₂ last) to the local orthonormal
// frame (t₁ along G_x, t₂ = N × t₁), ε = J⁻¹ E J⁻ᵀ with J_ai = G_a·t_i ([LW24] eq. 16).
Eigen::Matrix3d voigtFrameTransform(const Eigen::Vector3d& gx, const Eigen::Vector3d& gy) {
  const Eigen::Vector3d t1 = gx.normalized();
  const Eigen::Vector3d nrm = gx.cross(gy).normalized();
  const Eigen::Vector3d t2 = nrm.cross(t1);
  Eigen::Matrix2d j;
  j << gx.dot(t1), gx.dot(t2), gy.dot(t1), gy.dot(t2);
  const Eigen::Matrix2d c = j.inverse();
  Eigen::Matrix3d t;
  t << c(0, 0) * c(0, 0), c(0, 1) * c(0, 1), c(0, 0) * c(0, 1),  //
      c(1, 0) * c(1, 0), c(1, 1) * c(1, 1), c(1, 0) * c(1, 1),    //
      2 * c(0, 0) * c(1, 0), 2 * c(0, 1) * c(1, 1), c(0, 0) * c(1, 1) + c(0, 1) * c(1, 0);
  return t;
}

ShellPointKinematics shellKinematics(const Mat3x12& e_hat, const ShellShapeValues& s,
                                     const Eigen::Vector3d& metric0,
                                     const Eigen::Vector3d& curv0) {
  ShellPointKinematics kin;
  kin.gx.noalias() = e_hat * s.nx;
  kin.gy.noalias() = e_hat * s.ny;
  kin.rxx.noalias() = e_hat * s.nxx;
  kin.ryy.noalias() = e_hat * s.nyy;
  kin.rxy.noalias() = e_hat * s.nxy;
  const Eigen::Vector3d a = kin.gx.cross(kin.gy);
  kin.area_factor = a.norm();
  MASTROM_REQUIRE(kin.area_factor > 0.0 && std::isfinite(kin.area_factor), NumericalError,
                  "shell element: degenerate surface (|g_x × g_y| = ", kin.area_factor, ")");
  kin.n = a / kin.area_factor;
  kin.membrane << 0.5 * (kin.gx.squaredNorm() - metric0[0]),
      0.5 * (kin.gy.squaredNorm() - metric0[1]), kin.gx.dot(kin.gy) - metric0[2];
  kin.bending << kin.rxx.dot(kin.n) - curv0[0], kin.ryy.dot(kin.n) - curv0[1],
      2.0 * kin.rxy.dot(kin.n) - curv0[2];
  return kin;
}

Eigen::Matrix<double, 6, 1> shellStrainRates(const ShellPointKinematics& kin,
                                             const ShellShapeValues& s, const Mat3x12& edot_hat) {
  const Eigen::Vector3d gx_dot = edot_hat * s.nx, gy_dot = edot_hat * s.ny;
  const Eigen::Vector3d a_dot = gx_dot.cross(kin.gy) + kin.gx.cross(gy_dot);
  Eigen::Matrix<double, 6, 1> rates;
  rates[0] = kin.gx.dot(gx_dot);
  rates[1] = kin.gy.dot(gy_dot);
  rates[2] = kin.gx.dot(gy_dot) + kin.gy.dot(gx_dot);
  rates[3] = (edot_hat * s.nxx).dot(kin.n) + tangentialPart(kin, kin.rxx).dot(a_dot);
  rates[4] = (edot_hat * s.nyy).dot(kin.n) + tangentialPart(kin, kin.ryy).dot(a_dot);
  rates[5] = 2.0 * ((edot_hat * s.nxy).dot(kin.n) + tangentialPart(kin, kin.rxy).dot(a_dot));
  return rates;
}

void shellStrainRateJacobian(const ShellPointKinematics& kin, const ShellShapeValues& s,
                             const Mat3x12& edot_hat, Mat6x36& y) {
  y.setZero();
  const Eigen::Vector3d gx_dot = edot_hat * s.nx, gy_dot = edot_hat * s.ny;
  addOuter(gx_dot, s.nx, y, 0);
  addOuter(gy_dot, s.ny, y, 1);
  addOuter(gx_dot, s.ny, y, 2);
  addOuter(gy_dot, s.nx, y, 2);
  const double l = kin.area_factor;
  const Eigen::Vector3d a_dot = gx_dot.cross(kin.gy) + kin.gx.cross(gy_dot);
  const Eigen::Vector3d a_dot_tan = tangentialPart(kin, a_dot) * l;  // P ȧ
  const double n_adot = kin.n.dot(a_dot);
  const Eigen::Vector3d w[3] = {kin.rxx, kin.ryy, 2.0 * kin.rxy};
  const Eigen::Vector3d w_dot[3] = {edot_hat * s.nxx, edot_hat * s.nyy, 2.0 * (edot_hat * s.nxy)};
  const Vec12 nab[3] = {s.nxx, s.nyy, 2.0 * s.nxy};
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d v = tangentialPart(kin, w[c]);
    const Eigen::Vector3d u = tangentialPart(kin, w_dot[c]);
    const Eigen::Vector3d z =
        (kin.n.dot(w[c]) * a_dot_tan + n_adot * v * l) / (l * l) + (v.dot(a_dot) / l) * kin.n;
    const Eigen::Vector3d uz = u - z;
    addOuter(kin.gy.cross(uz) + gy_dot.cross(v), s.nx, y, 3 + c);
    addOuter(uz.cross(kin.gx) + v.cross(gx_dot), s.ny, y, 3 + c);
    addOuter(a_dot_tan / l, nab[c], y, 3 + c);
  }
}

void shellStrainJacobian(const ShellPointKinematics& kin, const ShellShapeValues& s, Mat6x36& b) {
  b.setZero();
  addOuter(kin.gx, s.nx, b, 0);
  addOuter(kin.gy, s.ny, b, 1);
  addOuter(kin.gx, s.ny, b, 2);
  addOuter(kin.gy, s.nx, b, 2);
  const Eigen::Vector3d w[3] = {kin.rxx, kin.ryy, 2.0 * kin.rxy};
  const Vec12 nab[3] = {s.nxx, s.nyy, 2.0 * s.nxy};
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d v = tangentialPart(kin, w[c]);
    addOuter(kin.n, nab[c], b, 3 + c);
    addOuter(kin.gy.cross(v), s.nx, b, 3 + c);
    addOuter(v.cross(kin.gx), s.ny, b, 3 + c);
  }
}

void addShellGeometricTangent(const ShellPointKinematics& kin, const ShellShapeValues& s,
                              const Eigen::Vector3d& sigma, const Eigen::Vector3d& moment,
                              Mat36& k) {
  // Membrane part: (σ₀ N_x N_xᵀ + σ₁ N_y N_yᵀ + σ₂ (N_x N_yᵀ + N_y N_xᵀ)) ⊗ I₃.
  Eigen::Matrix<double, 12, 12> g12;
  g12.noalias() = sigma[0] * s.nx * s.nx.transpose();
  g12.noalias() += sigma[1] * s.ny * s.ny.transpose();
  g12.noalias() += sigma[2] * (s.nx * s.ny.transpose() + s.ny * s.nx.transpose());

  // Bending part (see header). Scalar Kronecker term (N_y N_xᵀ − N_x N_yᵀ) ⊗ [V]×.
  const Eigen::Vector3d w = moment[0] * kin.rxx + moment[1] * kin.ryy + 2.0 * moment[2] * kin.rxy;
  const Vec12 n_m = moment[0] * s.nxx + moment[1] * s.nyy + 2.0 * moment[2] * s.nxy;
  const double l = kin.area_factor;
  const Eigen::Vector3d v = tangentialPart(kin, w);
  const Eigen::Matrix3d p = Eigen::Matrix3d::Identity() - kin.n * kin.n.transpose();
  const Eigen::Matrix3d h_a =
      -(v * kin.n.transpose() + kin.n * v.transpose() + (w.dot(kin.n) / l) * p) / l;
  const Eigen::Matrix<double, 12, 12> anti = s.ny * s.nx.transpose() - s.nx * s.ny.transpose();
  const Eigen::Matrix3d v_skew = skew(v);

  // A = ∂a/∂e (3×36), block j = −N_x[j][g_y]× + N_y[j][g_x]×.
  Eigen::Matrix<double, 3, 36> a_mat;
  const Eigen::Matrix3d gx_skew = skew(kin.gx), gy_skew = skew(kin.gy);
  for (int j = 0; j < 12; ++j)
    a_mat.block<3, 3>(0, 3 * j) = -s.nx[j] * gy_skew + s.ny[j] * gx_skew;
  const Eigen::Matrix<double, 3, 36> pa = (p / l) * a_mat;  // (P/l) A
  const Eigen::Matrix<double, 3, 36> ha = h_a * a_mat;      // H_a A

  for (int i = 0; i < 12; ++i) {
    // Rows of block-row i: S_M part N_M[i]·(P/l)A, plus Aᵀ-side terms, plus the Kronecker terms.
    k.block<3, 36>(3 * i, 0).noalias() += n_m[i] * pa;
    k.block<3, 36>(3 * i, 0).noalias() += a_mat.block<3, 3>(0, 3 * i).transpose() * ha;
    for (int j = 0; j < 12; ++j) {
      k.block<3, 3>(3 * i, 3 * j) += n_m[j] * pa.block<3, 3>(0, 3 * i).transpose() +
                                     anti(i, j) * v_skew;
      const double gij = g12(i, j);
      k(3 * i, 3 * j) += gij;
      k(3 * i + 1, 3 * j + 1) += gij;
      k(3 * i + 2, 3 * j + 2) += gij;
    }
  }
}

}  // namespace mastrom::fullorder
