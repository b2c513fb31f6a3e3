// The internal force of the ANCF thin shell at one quadrature point (docs/theory.md §2.2): the
// element's forces, tangents and strain energy (shell_element.cpp) and the batched kernel of time
// stepping (shell_force_kernel.inc, once per element of a chunk) call it. From the five fields of
// the point
//   F = [g_x, g_y, r_xx, r_yy, r_xy] = Ê·Dₛ    (Dₛ = the point's 12×5 derivative columns
//                                              [N_x N_y N_xx N_yy N_xy], Ê the 3×12 coordinates)
// it forms the surface invariants (n = a/l, a = g_x × g_y, l = |a|; the metric g_a·g_b; the normal
// curvatures w_c·n of w_c = r_xx, r_yy, 2 r_xy), the strains against the reference values
//   E = [½(g_x·g_x − G₀₀), ½(g_y·g_y − G₁₁), g_x·g_y − G₀₁],   k = [w_c·n] − k₀,
// their rates (shell_kinematics.hpp: the first variation along ė)
//   Ė = [g_x·ġ_x, g_y·ġ_y, g_x·ġ_y + g_y·ġ_x],   k̇_c = ẇ_c·n + (w_c·ȧ − (w_c·n)(n·ȧ))/l,
//   ȧ = ġ_x × g_y + g_x × ġ_y,
// the resultants [σ; m] by the material law (shell_material.hpp), and the force Bᵀ[σ; m], added by
// the caller as f̂ += C·Dₛᵀ with the 3×5 force directions
//   C = [σ₀g_x + σ₂g_y + g_y×V,  σ₁g_y + σ₂g_x + V×g_x,  m₀n,  m₁n,  2m₂n],
//   V = P W / l,  W = m₀r_xx + m₁r_yy + 2m₂r_xy,  P = I − n nᵀ
// (the first variation of shell_kinematics.hpp grouped by shape-function column).
//
// Plain scalars with constant indices only, so that the batched kernel's loop over elements inlines
// them and the compiler vectorises that loop across the elements.
#pragma once

#include <cmath>

#include "common/cpu_features.hpp"
#include "fullorder/shell_material.hpp"

namespace mastrom::fullorder {

/// F[k][c]: component c of field k (g_x, g_y, r_xx, r_yy, r_xy) — also the layout of the force
/// directions C, and of a column-major 3×5 matrix.
using ShellPointFields = double[5][3];

/// Reference data of one quadrature point, as the point force reads it.
struct ShellPointReference {
  double d[6] = {};        ///< D = w·dA·TᵀD̂T of the law (shell_material.hpp), d00 d01 d02 d11 d12 d22
  double metric0[3] = {};  ///< the reference's metric (ShellSurfaceInvariants::metric of e₀)
  double curv0[3] = {};    ///< the reference's normal curvatures (ShellSurfaceInvariants::curvature)
};

/// The deformed surface at a point.
struct ShellSurfaceInvariants {
  double n[3];          ///< unit normal a/l
  double inv_l;         ///< 1/l, l = |g_x × g_y|
  double area_sq;       ///< l²; not > 0 or not finite: the surface is degenerate at the point
  double metric[3];     ///< g_x·g_x, g_y·g_y, g_x·g_y
  double curvature[3];  ///< r_xx·n, r_yy·n, 2 r_xy·n
};

/// The invariants of the fields (also the reference values metric0, curv0 when F is e₀'s: computed
/// by the very operations the strains subtract them with, so e₀ is stress-free to the last bit).
MASTROM_ALWAYS_INLINE ShellSurfaceInvariants shellSurfaceInvariants(const ShellPointFields& f) {
  ShellSurfaceInvariants s;
  const double gx0 = f[0][0], gx1 = f[0][1], gx2 = f[0][2];
  const double gy0 = f[1][0], gy1 = f[1][1], gy2 = f[1][2];
  const double a0 = gx1 * gy2 - gx2 * gy1;
  const double a1 = gx2 * gy0 - gx0 * gy2;
  const double a2 = gx0 * gy1 - gx1 * gy0;
  s.area_sq = a0 * a0 + a1 * a1 + a2 * a2;
  s.inv_l = 1.0 / std::sqrt(s.area_sq);
  const double n0 = a0 * s.inv_l, n1 = a1 * s.inv_l, n2 = a2 * s.inv_l;
  s.n[0] = n0;
  s.n[1] = n1;
  s.n[2] = n2;
  s.curvature[0] = f[2][0] * n0 + f[2][1] * n1 + f[2][2] * n2;
  s.curvature[1] = f[3][0] * n0 + f[3][1] * n1 + f[3][2] * n2;
  s.curvature[2] = 2.0 * (f[4][0] * n0 + f[4][1] * n1 + f[4][2] * n2);
  s.metric[0] = gx0 * gx0 + gx1 * gx1 + gx2 * gx2;
  s.metric[1] = gy0 * gy0 + gy1 * gy1 + gy2 * gy2;
  s.metric[2] = gx0 * gy0 + gx1 * gy1 + gx2 * gy2;
  return s;
}

/// Everything the point force forms at one point (what the tangents need beside the force).
struct ShellPointState {
  ShellSurfaceInvariants surface;
  double strain[6];      ///< [E; k]
  double rate[6];        ///< [Ė; k̇] (not formed for ShellStressPart::kElastic)
  double resultants[6];  ///< [σ; m]
};

/// The strains [E; k] of the point, and with kRates their rates [Ė; k̇] from the rate fields Ḟ.
template <bool kRates>
MASTROM_ALWAYS_INLINE void shellPointStrains(const ShellPointFields& f, const ShellPointFields& fdot,
                                             const ShellPointReference& ref, ShellPointState& st) {
  const ShellSurfaceInvariants& s = st.surface;
  st.strain[0] = 0.5 * (s.metric[0] - ref.metric0[0]);
  st.strain[1] = 0.5 * (s.metric[1] - ref.metric0[1]);
  st.strain[2] = s.metric[2] - ref.metric0[2];
  st.strain[3] = s.curvature[0] - ref.curv0[0];
  st.strain[4] = s.curvature[1] - ref.curv0[1];
  st.strain[5] = s.curvature[2] - ref.curv0[2];
  if constexpr (kRates) {
    const double gx0 = f[0][0], gx1 = f[0][1], gx2 = f[0][2];
    const double gy0 = f[1][0], gy1 = f[1][1], gy2 = f[1][2];
    const double dx0 = fdot[0][0], dx1 = fdot[0][1], dx2 = fdot[0][2];
    const double dy0 = fdot[1][0], dy1 = fdot[1][1], dy2 = fdot[1][2];
    const double n0 = s.n[0], n1 = s.n[1], n2 = s.n[2];
    const double ad0 = (dx1 * gy2 - dx2 * gy1) + (gx1 * dy2 - gx2 * dy1);
    const double ad1 = (dx2 * gy0 - dx0 * gy2) + (gx2 * dy0 - gx0 * dy2);
    const double ad2 = (dx0 * gy1 - dx1 * gy0) + (gx0 * dy1 - gx1 * dy0);
    const double nad = n0 * ad0 + n1 * ad1 + n2 * ad2;
    st.rate[0] = gx0 * dx0 + gx1 * dx1 + gx2 * dx2;
    st.rate[1] = gy0 * dy0 + gy1 * dy1 + gy2 * dy2;
    st.rate[2] = (gx0 * dy0 + gx1 * dy1 + gx2 * dy2) + (gy0 * dx0 + gy1 * dx1 + gy2 * dx2);
    const double rn0 = fdot[2][0] * n0 + fdot[2][1] * n1 + fdot[2][2] * n2;
    const double rn1 = fdot[3][0] * n0 + fdot[3][1] * n1 + fdot[3][2] * n2;
    const double rn2 = fdot[4][0] * n0 + fdot[4][1] * n1 + fdot[4][2] * n2;
    const double wa0 = f[2][0] * ad0 + f[2][1] * ad1 + f[2][2] * ad2;
    const double wa1 = f[3][0] * ad0 + f[3][1] * ad1 + f[3][2] * ad2;
    const double wa2 = f[4][0] * ad0 + f[4][1] * ad1 + f[4][2] * ad2;
    st.rate[3] = rn0 + (wa0 - s.curvature[0] * nad) * s.inv_l;
    st.rate[4] = rn1 + (wa1 - s.curvature[1] * nad) * s.inv_l;
    st.rate[5] = 2.0 * (rn2 + (wa2 - 0.5 * s.curvature[2] * nad) * s.inv_l);
  }
}

/// The force directions C of the resultants [σ; m] (see the file comment): f̂ += C·Dₛᵀ.
MASTROM_ALWAYS_INLINE void shellForceDirections(const ShellPointFields& f,
                                                const ShellSurfaceInvariants& s,
                                                const double (&res)[6], ShellPointFields& dir) {
  const double gx0 = f[0][0], gx1 = f[0][1], gx2 = f[0][2];
  const double gy0 = f[1][0], gy1 = f[1][1], gy2 = f[1][2];
  const double n0 = s.n[0], n1 = s.n[1], n2 = s.n[2];
  const double s0 = res[0], s1 = res[1], s2 = res[2], m0 = res[3], m1 = res[4], m2 = res[5];
  // W = m₀ r_xx + m₁ r_yy + 2 m₂ r_xy, V = (W − n(n·W))/l.
  const double w0 = m0 * f[2][0] + m1 * f[3][0] + 2.0 * m2 * f[4][0];
  const double w1 = m0 * f[2][1] + m1 * f[3][1] + 2.0 * m2 * f[4][1];
  const double w2 = m0 * f[2][2] + m1 * f[3][2] + 2.0 * m2 * f[4][2];
  const double nw = n0 * w0 + n1 * w1 + n2 * w2;
  const double v0 = (w0 - n0 * nw) * s.inv_l, v1 = (w1 - n1 * nw) * s.inv_l,
               v2 = (w2 - n2 * nw) * s.inv_l;
  dir[0][0] = s0 * gx0 + s2 * gy0 + (gy1 * v2 - gy2 * v1);
  dir[0][1] = s0 * gx1 + s2 * gy1 + (gy2 * v0 - gy0 * v2);
  dir[0][2] = s0 * gx2 + s2 * gy2 + (gy0 * v1 - gy1 * v0);
  dir[1][0] = s1 * gy0 + s2 * gx0 + (v1 * gx2 - v2 * gx1);
  dir[1][1] = s1 * gy1 + s2 * gx1 + (v2 * gx0 - v0 * gx2);
  dir[1][2] = s1 * gy2 + s2 * gx2 + (v0 * gx1 - v1 * gx0);
  dir[2][0] = m0 * n0;
  dir[2][1] = m0 * n1;
  dir[2][2] = m0 * n2;
  dir[3][0] = m1 * n0;
  dir[3][1] = m1 * n1;
  dir[3][2] = m1 * n2;
  dir[4][0] = 2.0 * m2 * n0;
  dir[4][1] = 2.0 * m2 * n1;
  dir[4][2] = 2.0 * m2 * n2;
}

/// The point's internal force: fields F (and rate fields Ḟ, read unless kPart is kElastic) →
/// invariants → strains → resultants (the law, part kPart) → force directions C. The caller checks
/// st.surface.area_sq (degenerate surface) and adds C·Dₛᵀ.
template <ShellStressPart kPart>
MASTROM_ALWAYS_INLINE void shellPointForce(const ShellPointFields& f, const ShellPointFields& fdot,
                                           const ShellPointReference& ref,
                                           const ShellSectionScales& c, ShellPointState& st,
                                           ShellPointFields& dir) {
  st.surface = shellSurfaceInvariants(f);
  shellPointStrains<kPart != ShellStressPart::kElastic>(f, fdot, ref, st);
  shellResultants<kPart>(ref.d, c, st.strain, st.rate, st.resultants);
  shellForceDirections(f, st.surface, st.resultants, dir);
}

}  // namespace mastrom::fullorder
