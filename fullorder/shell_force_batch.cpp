// Lane-parallel evaluation of the shell internal force (see the header). The algebra per point is
// that of addShellPointInternalForce (shell_kinematics.cpp), written with every scalar an array
// over kLanes elements; see that function for the derivation of each line.
#include "fullorder/shell_force_batch.hpp"

#include <cmath>
#include <limits>

#include "common/cpu_features.hpp"
#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {

constexpr int W = ShellForceBatch::kLanes;
constexpr int kFieldCount = 5;  // g_x, g_y, r_xx, r_yy, r_xy (columns of the derivative table)

/// Inputs and output of one chunk, lane index fastest: x[j][c][l] is component c of nodal vector j
/// of lane l (Ê(c, j) of ShellElement), likewise ẋ and the force f.
struct LaneBlock {
  alignas(64) double x[12][3][W];
  alignas(64) double xdot[12][3][W];
  alignas(64) double f[12][3][W];
};

/// Reference data of one point: reference[k][l] with k = d00 d01 d02 d11 d12 d22 (d_eff,
/// symmetric), m0 m1 m2 (metric0), k0 k1 k2 (curv0). Returns the first lane (0-based) whose surface
/// is degenerate at some point, or −1.
template <bool kDamped>
MASTROM_ALWAYS_INLINE int chunkKernel(LaneBlock& b, const double* material, const double* reference,
                                      const ShellShapeTable& table) {
  const double* cm = material;
  const double* cb = material + W;
  const double* mu = material + 2 * W;
  int degenerate = -1;
  for (double(&fj)[3][W] : b.f)
    for (double(&fc)[W] : fj)
      for (double& v : fc) v = 0.0;
  const std::size_t points = table.derivatives.size();
  for (std::size_t p = 0; p < points; ++p) {
    const double* dt = table.derivatives[p].data();  // 12×5, column-major: D(j, f) = dt[j + 12 f]
    const double* ref = reference + p * 12 * W;
    // Fields (and rates) at the point: fld(k, c) = Σ_j D(j, k) x(j, c), summed over j in
    // registers (one load per multiply-add; accumulating in memory costs two loads and a store).
    alignas(64) double fld[kFieldCount][3][W];
    alignas(64) double rate[kFieldCount][3][W];
    for (int k = 0; k < kFieldCount; ++k)
      for (int c = 0; c < 3; ++c) {
        double acc[W] = {}, acc_rate[W] = {};
        for (int j = 0; j < 12; ++j) {
          const double d = dt[j + 12 * k];
          for (int l = 0; l < W; ++l) {
            acc[l] += d * b.x[j][c][l];
            if constexpr (kDamped) acc_rate[l] += d * b.xdot[j][c][l];
          }
        }
        for (int l = 0; l < W; ++l) {
          fld[k][c][l] = acc[l];
          rate[k][c][l] = kDamped ? acc_rate[l] : 0.0;
        }
      }
    alignas(64) double dir[kFieldCount][3][W];
    alignas(64) double area_sq[W];
    for (int l = 0; l < W; ++l) {
      const double gx0 = fld[0][0][l], gx1 = fld[0][1][l], gx2 = fld[0][2][l];
      const double gy0 = fld[1][0][l], gy1 = fld[1][1][l], gy2 = fld[1][2][l];
      const double a0 = gx1 * gy2 - gx2 * gy1;
      const double a1 = gx2 * gy0 - gx0 * gy2;
      const double a2 = gx0 * gy1 - gx1 * gy0;
      const double l2 = a0 * a0 + a1 * a1 + a2 * a2;
      area_sq[l] = l2;
      const double len = std::sqrt(l2);
      const double inv = 1.0 / len;
      const double n0 = a0 * inv, n1 = a1 * inv, n2 = a2 * inv;
      // w_c·n for r_xx, r_yy, 2 r_xy.
      const double wn0 = fld[2][0][l] * n0 + fld[2][1][l] * n1 + fld[2][2][l] * n2;
      const double wn1 = fld[3][0][l] * n0 + fld[3][1][l] * n1 + fld[3][2][l] * n2;
      const double wn2 = 2.0 * (fld[4][0][l] * n0 + fld[4][1][l] * n1 + fld[4][2][l] * n2);
      const double* r = ref + l;
      double e0 = 0.5 * ((gx0 * gx0 + gx1 * gx1 + gx2 * gx2) - r[6 * W]);
      double e1 = 0.5 * ((gy0 * gy0 + gy1 * gy1 + gy2 * gy2) - r[7 * W]);
      double e2 = (gx0 * gy0 + gx1 * gy1 + gx2 * gy2) - r[8 * W];
      double k0 = wn0 - r[9 * W], k1 = wn1 - r[10 * W], k2 = wn2 - r[11 * W];
      if constexpr (kDamped) {
        // Ė and k̇ (shellStrainRates): ȧ = ġ_x × g_y + g_x × ġ_y.
        const double dx0 = rate[0][0][l], dx1 = rate[0][1][l], dx2 = rate[0][2][l];
        const double dy0 = rate[1][0][l], dy1 = rate[1][1][l], dy2 = rate[1][2][l];
        const double ad0 = (dx1 * gy2 - dx2 * gy1) + (gx1 * dy2 - gx2 * dy1);
        const double ad1 = (dx2 * gy0 - dx0 * gy2) + (gx2 * dy0 - gx0 * dy2);
        const double ad2 = (dx0 * gy1 - dx1 * gy0) + (gx0 * dy1 - gx1 * dy0);
        const double nad = n0 * ad0 + n1 * ad1 + n2 * ad2;
        const double m = mu[l];
        e0 += m * (gx0 * dx0 + gx1 * dx1 + gx2 * dx2);
        e1 += m * (gy0 * dy0 + gy1 * dy1 + gy2 * dy2);
        e2 += m * ((gx0 * dy0 + gx1 * dy1 + gx2 * dy2) + (gy0 * dx0 + gy1 * dx1 + gy2 * dx2));
        const double rn0 = rate[2][0][l] * n0 + rate[2][1][l] * n1 + rate[2][2][l] * n2;
        const double rn1 = rate[3][0][l] * n0 + rate[3][1][l] * n1 + rate[3][2][l] * n2;
        const double rn2 = rate[4][0][l] * n0 + rate[4][1][l] * n1 + rate[4][2][l] * n2;
        const double wa0 = fld[2][0][l] * ad0 + fld[2][1][l] * ad1 + fld[2][2][l] * ad2;
        const double wa1 = fld[3][0][l] * ad0 + fld[3][1][l] * ad1 + fld[3][2][l] * ad2;
        const double wa2 = fld[4][0][l] * ad0 + fld[4][1][l] * ad1 + fld[4][2][l] * ad2;
        k0 += m * (rn0 + (wa0 - wn0 * nad) * inv);
        k1 += m * (rn1 + (wa1 - wn1 * nad) * inv);
        k2 += m * 2.0 * (rn2 + (wa2 - 0.5 * wn2 * nad) * inv);
      }
      // σ = cm·D̂e, M = cb·D̂k with the symmetric d_eff.
      const double d00 = r[0], d01 = r[W], d02 = r[2 * W], d11 = r[3 * W], d12 = r[4 * W],
                   d22 = r[5 * W];
      const double s0 = cm[l] * (d00 * e0 + d01 * e1 + d02 * e2);
      const double s1 = cm[l] * (d01 * e0 + d11 * e1 + d12 * e2);
      const double s2 = cm[l] * (d02 * e0 + d12 * e1 + d22 * e2);
      const double m0 = cb[l] * (d00 * k0 + d01 * k1 + d02 * k2);
      const double m1 = cb[l] * (d01 * k0 + d11 * k1 + d12 * k2);
      const double m2 = cb[l] * (d02 * k0 + d12 * k1 + d22 * k2);
      // w = M₀ r_xx + M₁ r_yy + 2 M₂ r_xy, v = (w − n(n·w))/l.
      const double w0 = m0 * fld[2][0][l] + m1 * fld[3][0][l] + 2.0 * m2 * fld[4][0][l];
      const double w1 = m0 * fld[2][1][l] + m1 * fld[3][1][l] + 2.0 * m2 * fld[4][1][l];
      const double w2 = m0 * fld[2][2][l] + m1 * fld[3][2][l] + 2.0 * m2 * fld[4][2][l];
      const double nw = n0 * w0 + n1 * w1 + n2 * w2;
      const double v0 = (w0 - n0 * nw) * inv, v1 = (w1 - n1 * nw) * inv, v2 = (w2 - n2 * nw) * inv;
      // dir₀ = σ₀g_x + σ₂g_y + g_y × v, dir₁ = σ₁g_y + σ₂g_x + v × g_x, dir₂…₄ = (M₀, M₁, 2M₂) n.
      dir[0][0][l] = s0 * gx0 + s2 * gy0 + (gy1 * v2 - gy2 * v1);
      dir[0][1][l] = s0 * gx1 + s2 * gy1 + (gy2 * v0 - gy0 * v2);
      dir[0][2][l] = s0 * gx2 + s2 * gy2 + (gy0 * v1 - gy1 * v0);
      dir[1][0][l] = s1 * gy0 + s2 * gx0 + (v1 * gx2 - v2 * gx1);
      dir[1][1][l] = s1 * gy1 + s2 * gx1 + (v2 * gx0 - v0 * gx2);
      dir[1][2][l] = s1 * gy2 + s2 * gx2 + (v0 * gx1 - v1 * gx0);
      dir[2][0][l] = m0 * n0;
      dir[2][1][l] = m0 * n1;
      dir[2][2][l] = m0 * n2;
      dir[3][0][l] = m1 * n0;
      dir[3][1][l] = m1 * n1;
      dir[3][2][l] = m1 * n2;
      dir[4][0][l] = 2.0 * m2 * n0;
      dir[4][1][l] = 2.0 * m2 * n1;
      dir[4][2][l] = 2.0 * m2 * n2;
    }
    for (int l = 0; l < W; ++l)
      if (degenerate < 0 &&
          !(area_sq[l] > 0.0 && area_sq[l] < std::numeric_limits<double>::infinity()))
        degenerate = l;
    // Scatter: f(c, j) += Σ_k dir_k(c) D(j, k), summed over k in registers.
    for (int j = 0; j < 12; ++j)
      for (int c = 0; c < 3; ++c) {
        double acc[W];
        for (int l = 0; l < W; ++l) acc[l] = b.f[j][c][l];
        for (int k = 0; k < kFieldCount; ++k) {
          const double d = dt[j + 12 * k];
          for (int l = 0; l < W; ++l) acc[l] += d * dir[k][c][l];
        }
        for (int l = 0; l < W; ++l) b.f[j][c][l] = acc[l];
      }
  }
  return degenerate;
}

int kernelBaseline(LaneBlock& b, const double* material, const double* reference,
                   const ShellShapeTable& table, bool damped) {
  return damped ? chunkKernel<true>(b, material, reference, table)
                : chunkKernel<false>(b, material, reference, table);
}

#if MASTROM_HAVE_AVX2_KERNELS
// The same body compiled for AVX2 + FMA (4 lanes per instruction, fused multiply-add); chosen at
// run time only on CPUs that have both (ShellForceBatch constructor).
__attribute__((target("avx2,fma"))) int kernelAvx2(LaneBlock& b, const double* material,
                                                   const double* reference,
                                                   const ShellShapeTable& table, bool damped) {
  return damped ? chunkKernel<true>(b, material, reference, table)
                : chunkKernel<false>(b, material, reference, table);
}
#endif

}  // namespace

ShellForceBatch::ShellForceBatch(const std::vector<const ShellElement*>& elements,
                                 const std::vector<std::array<int, 36>>& dofs) {
  MASTROM_REQUIRE(elements.size() == dofs.size(), InputError,
                  "shell force batch: ", elements.size(), " elements but ", dofs.size(),
                  " dof lists");
  element_count_ = static_cast<int>(elements.size());
  if (elements.empty()) return;
  table_ = elements.front()->shapeTable();
  const std::size_t points = table_->derivatives.size();
  for (std::size_t first = 0; first < elements.size(); first += W) {
    Chunk chunk;
    chunk.first_element = static_cast<int>(first);
    chunk.lanes = static_cast<int>(std::min<std::size_t>(W, elements.size() - first));
    chunk.reference.assign(points * kPointFields * W, 0.0);
    for (int l = 0; l < W; ++l) {
      // Padding lanes compute a copy of lane 0 (well defined, never scattered).
      const std::size_t k = first + static_cast<std::size_t>(l < chunk.lanes ? l : 0);
      const ShellElement& el = *elements[k];
      MASTROM_REQUIRE(el.shapeTable() == table_, InputError, "shell force batch: element ", k,
                      " has a different shape table");
      for (int i = 0; i < 36; ++i) chunk.dofs[static_cast<std::size_t>(i)][l] = dofs[k][i];
      const ShellSection& s = el.section();
      const double h = s.thickness_m, young = s.youngs_modulus_pa;
      chunk.material[0][l] = young * h;
      chunk.material[1][l] = young * h * h * h / 12.0;
      chunk.material[2][l] = s.damping_s;
      chunk.damped = chunk.damped || s.damping_s != 0.0;
      for (std::size_t p = 0; p < points; ++p) {
        const ShellElement::QuadPoint& qp = el.quadPoint(p);
        const double values[kPointFields] = {qp.d_eff(0, 0),  qp.d_eff(0, 1),  qp.d_eff(0, 2),
                                             qp.d_eff(1, 1),  qp.d_eff(1, 2),  qp.d_eff(2, 2),
                                             qp.e0_metric[0], qp.e0_metric[1], qp.e0_metric[2],
                                             qp.k0[0],        qp.k0[1],        qp.k0[2]};
        for (int v = 0; v < kPointFields; ++v)
          chunk.reference[(p * kPointFields + static_cast<std::size_t>(v)) * W +
                          static_cast<std::size_t>(l)] = values[v];
      }
    }
    chunks_.push_back(std::move(chunk));
  }
  use_avx2_ = cpuHasAvx2Fma();
}

void ShellForceBatch::evaluateChunk(const Chunk& chunk, const double* q, const double* qdot,
                                    double* f_lanes) const {
  LaneBlock b;
  const bool damped = chunk.damped;
  for (int j = 0; j < 12; ++j)
    for (int c = 0; c < 3; ++c) {
      const auto& idx = chunk.dofs[static_cast<std::size_t>(3 * j + c)];
      for (int l = 0; l < W; ++l) b.x[j][c][l] = q[idx[l]];
      if (damped)
        for (int l = 0; l < W; ++l) b.xdot[j][c][l] = qdot[idx[l]];
    }
  const double* material = chunk.material[0].data();
  int bad = -1;
#if MASTROM_HAVE_AVX2_KERNELS
  if (use_avx2_)
    bad = kernelAvx2(b, material, chunk.reference.data(), *table_, damped);
  else
#endif
    bad = kernelBaseline(b, material, chunk.reference.data(), *table_, damped);
  MASTROM_REQUIRE(bad < 0, NumericalError, "shell element ", chunk.first_element + bad,
                  ": degenerate surface (|g_x x g_y| = 0 or not finite at a quadrature point)");
  for (int j = 0; j < 12; ++j)
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l < W; ++l) f_lanes[(3 * j + c) * W + l] = b.f[j][c][l];
}

void ShellForceBatch::subtractInternalForces(const double* q, const double* qdot, double* f) const {
  alignas(64) double f_lanes[36 * W];
  for (int c = 0; c < chunkCount(); ++c) {
    evaluateChunkForces(c, q, qdot, f_lanes);
    subtractChunkForces(c, f_lanes, f);
  }
}

void ShellForceBatch::evaluateChunkForces(int chunk, const double* q, const double* qdot,
                                          double* lanes) const {
  evaluateChunk(chunks_[static_cast<std::size_t>(chunk)], q, qdot, lanes);
}

void ShellForceBatch::subtractChunkForces(int chunk, const double* lanes, double* f) const {
  const Chunk& c = chunks_[static_cast<std::size_t>(chunk)];
  // Element by element, in element order (the order of the per-element loop it replaces).
  for (int l = 0; l < c.lanes; ++l)
    for (int i = 0; i < 36; ++i) f[c.dofs[static_cast<std::size_t>(i)][l]] -= lanes[i * W + l];
}

void ShellForceBatch::internalForces(const double* q, const double* qdot,
                                     std::vector<double>& out) const {
  out.assign(static_cast<std::size_t>(element_count_) * 36, 0.0);
  alignas(64) double f_lanes[36 * W];
  for (const Chunk& chunk : chunks_) {
    evaluateChunk(chunk, q, qdot, f_lanes);
    for (int l = 0; l < chunk.lanes; ++l)
      for (int i = 0; i < 36; ++i)
        out[static_cast<std::size_t>(chunk.first_element + l) * 36 + static_cast<std::size_t>(i)] =
            f_lanes[i * W + l];
  }
}

}  // namespace mastrom::fullorder
