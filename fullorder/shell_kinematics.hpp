// Point-wise kinematics of the ANCF thin shell and their first and second derivatives with respect
// to the element coordinates e ∈ R³⁶ (docs/theory.md §2.2). Internal to shell_element.cpp;
// separated so the element file stays about quadrature and assembly, and so the derivatives can be
// tested alone.
//
// All fields are linear in e: with Ê the 3×12 view of e, g_x = Ê N_x, g_y = Ê N_y, r_,ab = Ê N_ab.
//   membrane strain  E = [½(g_x·g_x − Gxx), ½(g_y·g_y − Gyy), g_x·g_y − Gxy]      (quadratic in e)
//   curvature        k = [r_xx·n − k0₀, r_yy·n − k0₁, 2 r_xy·n − k0₂],  n = a/|a|,  a = g_x × g_y
// First variation of r_,ab·n:  δ(w·n) = δw·n + δa·v,  v = P w / l,  P = I − n nᵀ,  l = |a|,
//   δa·v = δg_x·(g_y × v) + δg_y·(v × g_x).
// Second variation (for the exact tangent), with W = Σ m_c w_c the moment-weighted field:
//   H = S_Mᵀ(P/l)A + Aᵀ(P/l)S_M + Aᵀ H_a A + (N_y N_xᵀ − N_x N_yᵀ) ⊗ [V]×,
//   A = ∂a/∂e = −[g_y]× S_x + [g_x]× S_y,   V = P W / l,
//   H_a = ∂²(W·n)/∂a² = −(V nᵀ + n Vᵀ + (W·n)/l · P)/l.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "fullorder/shell_shape.hpp"

namespace mastrom::fullorder {

using Mat3x12 = Eigen::Matrix<double, 3, 12>;
using Mat6x36 = Eigen::Matrix<double, 6, 36>;
using Mat36 = Eigen::Matrix<double, 36, 36>;

/// Deformed-state quantities at one quadrature point.
struct ShellPointKinematics {
  Eigen::Vector3d gx, gy, rxx, ryy, rxy;  ///< tangent vectors and second derivatives
  Eigen::Vector3d n;                      ///< unit normal
  double area_factor = 0.0;               ///< l = |g_x × g_y|
  Eigen::Vector3d membrane;               ///< E (Voigt, parameter coordinates, 2E_xy last)
  Eigen::Vector3d bending;                ///< k (Voigt, 2κ_xy last)
};

/// T maps covariant parameter-coordinate strains (Voigt, 2E₁₂ last) of a point with reference
/// tangents (G_x, G_y) to the local orthonormal frame (t₁ along G_x, t₂ = N × t₁, N ∥ G_x × G_y):
/// ε = T E ([LW24] eq. 16; docs/theory.md §6.1). The element's energy and its stresses both use it.
Eigen::Matrix3d voigtFrameTransform(const Eigen::Vector3d& gx, const Eigen::Vector3d& gy);

/// Evaluate the kinematics. e_hat = element coordinates viewed as 3×12.
/// @param metric0 [G_x·G_x, G_y·G_y, G_x·G_y] of the reference state
/// @param curv0   [R_xx·N, R_yy·N, 2R_xy·N] of the reference state
ShellPointKinematics shellKinematics(const Mat3x12& e_hat, const ShellShapeValues& s,
                                     const Eigen::Vector3d& metric0,
                                     const Eigen::Vector3d& curv0);

/// Strain rates Ė = ∂E/∂e·ė (first three) and k̇ = ∂k/∂e·ė (last three) without forming ∂/∂e:
///   Ė = [g_x·ġ_x, g_y·ġ_y, g_x·ġ_y + g_y·ġ_x],  k̇_c = ẇ_c·n + v_c·ȧ,  ȧ = ġ_x × g_y + g_x × ġ_y.
Eigen::Matrix<double, 6, 1> shellStrainRates(const ShellPointKinematics& kin,
                                             const ShellShapeValues& s, const Mat3x12& edot_hat);

/// ∂(Ė, k̇)/∂e at fixed ė (6×36), i.e. the rows (∂²ε_c/∂e²)·ė, without forming second derivatives:
/// with v = P w/l, u = P ẇ/l and z = [(n·w) P ȧ + (n·ȧ) P w]/l² + (v·ȧ) n/l,
///   ∂k̇/∂Ê = (g_y × (u − z) + ġ_y × v) N_xᵀ + ((u − z) × g_x + v × ġ_x) N_yᵀ + (P ȧ/l) N_wᵀ.
void shellStrainRateJacobian(const ShellPointKinematics& kin, const ShellShapeValues& s,
                             const Mat3x12& edot_hat, Mat6x36& y);

/// Strain-displacement rows: B.topRows<3>() = ∂E/∂e, B.bottomRows<3>() = ∂k/∂e.
void shellStrainJacobian(const ShellPointKinematics& kin, const ShellShapeValues& s, Mat6x36& b);

/// Add Σ_c σ_c ∂²E_c/∂e² + Σ_c m_c ∂²k_c/∂e² (the stress-dependent, "geometric" part of the tangent).
void addShellGeometricTangent(const ShellPointKinematics& kin, const ShellShapeValues& s,
                              const Eigen::Vector3d& sigma, const Eigen::Vector3d& moment,
                              Mat36& k);

}  // namespace mastrom::fullorder
