// Lane-parallel evaluation of the shell internal force (see the header). The algebra per point is
// that of shellPointForce (shell_point_force.hpp, which every ShellElement force calls), written
// here with every scalar an array over kLanes elements, expression for expression: calling
// shellPointForce per lane made this kernel 2.1 times slower (benchmarks/README.md), so this copy
// stays and tests/fullorder/test_shell_force_batch.cpp holds it to the element's forces.
#include "fullorder/shell_force_batch.hpp"

#include <cmath>
#include <limits>

#include "common/cpu_features.hpp"
#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {

constexpr int W = ShellForceBatch::kLanes;
constexpr int kFieldCount = 5;  // g_x, g_y, r_xx, r_yy, r_xy (columns of the derivative table)

// The kernel works in the monomial basis of the shape functions (docs/theory.md §2.2;
// shell_shape.hpp): the 12 functions span exactly the monomials ξ^p η^q of
// kShellMonomialXiPower/EtaPower, so per element and component the 12 nodal values are first mapped
// to 12 monomial coefficients, c_i = Σ_j C(j, i) x_j, and each field at a point is Σ_i ∂_k
// m_i(point) c_i. A derivative sees only the monomials it does not annihilate — 8 (g_x), 8 (g_y), 4
// (r_xx), 4 (r_yy), 5 (r_xy): 29 multiply-adds per point and component instead of 12 × 5 = 60. The
// scatter is the transpose: the point's directions are accumulated into 12 monomial moments (29 per
// point), mapped back to the nodes by C once per element. C has 84 nonzeros outside the constant
// monomial (which no field sees), so a 4×4 rule costs 84 + 16·29 = 548 instead of 960 per component
// and pass.

/// Derivative order (in ξ, in η) of each field.
constexpr int kFieldXiOrder[kFieldCount] = {1, 0, 2, 0, 1};
constexpr int kFieldEtaOrder[kFieldCount] = {0, 1, 0, 2, 1};

constexpr bool fieldSees(int field, int monomial) {
  return kShellMonomialXiPower[monomial] >= kFieldXiOrder[field] &&
         kShellMonomialEtaPower[monomial] >= kFieldEtaOrder[field];
}

/// The nonzeros of a fixed Rows × Cols pattern, row by row (`terms`, row r at [begin[r],
/// begin[r + 1])) and column by column as indices into that list (`by_col`, column c at
/// [by_col_begin[c], by_col_begin[c + 1])): the gather walks one order, the scatter the other.
template <int Rows, int Cols, int Count>
struct PatternLists {
  struct Term {
    int row = 0, col = 0;
  };
  std::array<Term, Count> terms{};
  std::array<int, Rows + 1> begin{};
  std::array<int, Count> by_col{};
  std::array<int, Cols + 1> by_col_begin{};
};
template <int Rows, int Cols, class Has>
constexpr int countPattern(Has has) {
  int n = 0;
  for (int r = 0; r < Rows; ++r)
    for (int c = 0; c < Cols; ++c) n += has(r, c) ? 1 : 0;
  return n;
}
template <int Rows, int Cols, int Count, class Has>
constexpr PatternLists<Rows, Cols, Count> makePatternLists(Has has) {
  PatternLists<Rows, Cols, Count> lists;
  int n = 0;
  for (int r = 0; r < Rows; ++r) {
    lists.begin[r] = n;
    for (int c = 0; c < Cols; ++c)
      if (has(r, c)) lists.terms[n++] = {r, c};
  }
  lists.begin[Rows] = n;
  n = 0;
  for (int c = 0; c < Cols; ++c) {
    lists.by_col_begin[c] = n;
    for (int t = 0; t < Count; ++t)
      if (lists.terms[t].col == c) lists.by_col[n++] = t;
  }
  lists.by_col_begin[Cols] = n;
  return lists;
}

/// The monomial derivatives the fields need: row = field k, column = monomial i; field k gets
/// Σ ∂_k m_i(point) c_i. The per-point table stores them in row order (gather order).
constexpr auto kFieldSees = [](int field, int monomial) { return fieldSees(field, monomial); };
constexpr int kFieldTermCount = countPattern<kFieldCount, 12>(kFieldSees);
static_assert(kFieldTermCount == 29, "8 + 8 + 4 + 4 + 5 monomial derivatives");
constexpr auto kFieldTerms = makePatternLists<kFieldCount, 12, kFieldTermCount>(kFieldSees);

/// The nonzeros of C (shellMonomialCoefficients) outside the constant monomial: row = monomial i,
/// column = node j (c_i = Σ_j C(j, i) x_j; the stored values use row order). Their positions do
/// not depend on the element's size (only the slope columns scale, with a or b), so the kernel's
/// loops over them have fixed bounds.
constexpr ShellMonomialMatrix kUnitCoefficients = shellMonomialCoefficients(1.0, 1.0);
constexpr auto kTransformHas = [](int monomial, int node) {
  return monomial > 0 && kUnitCoefficients[node][monomial] != 0.0;
};
constexpr int kTransformTermCount = countPattern<12, 12>(kTransformHas);
static_assert(kTransformTermCount == 84, "the ACM functions have 84 nonconstant monomial terms");
constexpr auto kTransformTerms = makePatternLists<12, 12, kTransformTermCount>(kTransformHas);

/// Running sums of a 3-vector over the lanes, kept in registers: every sum below takes all three
/// components at once, so one step of a sum is 3·W/4 independent multiply-adds (AVX2) — enough to
/// hide the latency of the fused multiply-add, which a single component's two does not.
struct Sums3 {
  double v[3][W] = {};
  Sums3() = default;
  MASTROM_ALWAYS_INLINE explicit Sums3(const double (&start)[3][W]) {
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l < W; ++l) v[c][l] = start[c][l];
  }
  /// v += d · x
  MASTROM_ALWAYS_INLINE void add(double d, const double (&x)[3][W]) {
    for (int l = 0; l < W; ++l) v[0][l] += d * x[0][l];
    for (int l = 0; l < W; ++l) v[1][l] += d * x[1][l];
    for (int l = 0; l < W; ++l) v[2][l] += d * x[2][l];
  }
  MASTROM_ALWAYS_INLINE void store(double (&out)[3][W]) const {
    for (int c = 0; c < 3; ++c)
      for (int l = 0; l < W; ++l) out[c][l] = v[c][l];
  }
};

/// coef(i) = Σ_j C(j, i) x(j) for the monomials i ≥ 1 (transform: C's nonzeros, see KernelShape).
MASTROM_ALWAYS_INLINE void toMonomials(const double* transform, const double (&x)[12][3][W],
                                       double (&coef)[12][3][W]) {
  for (int i = 1; i < 12; ++i) {
    Sums3 acc;
    for (int t = kTransformTerms.begin[i]; t < kTransformTerms.begin[i + 1]; ++t)
      acc.add(transform[t], x[kTransformTerms.terms[t].col]);
    acc.store(coef[i]);
  }
}

/// fld(k) = Σ_i ∂_k m_i coef(i) at one point (dm: its kFieldTermCount derivatives).
MASTROM_ALWAYS_INLINE void gatherFields(const double* dm, const double (&coef)[12][3][W],
                                        double (&fld)[kFieldCount][3][W]) {
  for (int k = 0; k < kFieldCount; ++k) {
    Sums3 acc;
    for (int t = kFieldTerms.begin[k]; t < kFieldTerms.begin[k + 1]; ++t)
      acc.add(dm[t], coef[kFieldTerms.terms[t].col]);
    acc.store(fld[k]);
  }
}

/// Inputs and output of one chunk, lane index fastest: x[j][c][l] is component c of nodal vector j
/// of lane l (Ê(c, j) of ShellElement), likewise ẋ and the force f.
struct LaneBlock {
  alignas(64) double x[12][3][W];
  alignas(64) double xdot[12][3][W];
  alignas(64) double f[12][3][W];
};

/// What the kernel reads of the shape, flat: per point the kFieldTermCount monomial derivatives
/// (gather order, chain rule 2/a, 2/b folded in) and the kTransformTermCount values of C.
struct KernelShape {
  std::size_t points = 0;
  const double* field_terms = nullptr;
  const double* transform = nullptr;
};

/// Reference data of one point: reference[k][l] with k = d00 d01 d02 d11 d12 d22 (D of the law,
/// ShellPointReference::d), m0 m1 m2 (metric0), k0 k1 k2 (curv0). Returns the first lane (0-based) whose surface
/// is degenerate at some point, or −1.
/// With kReference the kernel only writes the metric and curvature invariants of b.x into
/// reference_out (the same layout, fields 6…11) — by the very operations the force pass subtracts
/// them with, so the reference state is stress-free to the last bit (docs/theory.md §2.2: strains
/// against the interpolated e₀).
template <bool kDamped, bool kReference = false>
MASTROM_ALWAYS_INLINE int chunkKernel(LaneBlock& b, const double* material, const double* reference,
                                      double* reference_out, const KernelShape& shape) {
  const double* cm = material;
  const double* cb = material + W;
  const double* mu = material + 2 * W;
  int degenerate = -1;
  // Monomial coefficients of the fields (and rates): coef(i, c) = Σ_j C(j, i) x(j, c). Row 0 (the
  // constant, a rigid translation) is never needed.
  alignas(64) double coef[12][3][W];
  alignas(64) double coef_rate[12][3][W];
  alignas(64) double moment[12][3][W];  // Σ over points of ∂_k m_i · dir_k
  toMonomials(shape.transform, b.x, coef);
  if constexpr (kDamped) toMonomials(shape.transform, b.xdot, coef_rate);
  for (int i = 1; i < 12; ++i) Sums3().store(moment[i]);
  for (std::size_t p = 0; p < shape.points; ++p) {
    const double* dm = shape.field_terms + p * kFieldTermCount;
    const double* ref = reference + p * 12 * W;
    // Fields (and rates) at the point: fld(k, c) = Σ_i ∂_k m_i coef(i, c).
    alignas(64) double fld[kFieldCount][3][W];
    alignas(64) double rate[kFieldCount][3][W];
    gatherFields(dm, coef, fld);
    if constexpr (kDamped) gatherFields(dm, coef_rate, rate);
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
      const double g11 = gx0 * gx0 + gx1 * gx1 + gx2 * gx2;
      const double g22 = gy0 * gy0 + gy1 * gy1 + gy2 * gy2;
      const double g12 = gx0 * gy0 + gx1 * gy1 + gx2 * gy2;
      if constexpr (kReference) {
        double* out = reference_out + p * 12 * W + l;
        out[6 * W] = g11;
        out[7 * W] = g22;
        out[8 * W] = g12;
        out[9 * W] = wn0;
        out[10 * W] = wn1;
        out[11 * W] = wn2;
        continue;
      }
      double e0 = 0.5 * (g11 - r[6 * W]);
      double e1 = 0.5 * (g22 - r[7 * W]);
      double e2 = g12 - r[8 * W];
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
    if constexpr (kReference) continue;
    // Scatter into the moments: moment(i, c) += Σ_k ∂_k m_i dir_k(c).
    for (int i = 1; i < 12; ++i) {
      Sums3 acc(moment[i]);
      for (int s = kFieldTerms.by_col_begin[i]; s < kFieldTerms.by_col_begin[i + 1]; ++s) {
        const int t = kFieldTerms.by_col[s];
        acc.add(dm[t], dir[kFieldTerms.terms[t].row]);
      }
      acc.store(moment[i]);
    }
  }
  if constexpr (kReference) return degenerate;
  // Back to the nodes: f(j, c) = Σ_i C(j, i) moment(i, c).
  for (int j = 0; j < 12; ++j) {
    Sums3 acc;
    for (int s = kTransformTerms.by_col_begin[j]; s < kTransformTerms.by_col_begin[j + 1]; ++s) {
      const int t = kTransformTerms.by_col[s];
      acc.add(shape.transform[t], moment[kTransformTerms.terms[t].row]);
    }
    acc.store(b.f[j]);
  }
  return degenerate;
}

int kernelBaseline(LaneBlock& b, const double* material, const double* reference,
                   const KernelShape& shape, bool damped) {
  return damped ? chunkKernel<true>(b, material, reference, nullptr, shape)
                : chunkKernel<false>(b, material, reference, nullptr, shape);
}
/// The material of the reference pass (read by no line it runs).
constexpr double kNoMaterial[3 * W] = {};
int referenceBaseline(LaneBlock& b, double* reference, const KernelShape& shape) {
  return chunkKernel<false, true>(b, kNoMaterial, reference, reference, shape);
}

#if MASTROM_HAVE_AVX2_KERNELS
// The same body compiled for AVX2 + FMA (4 lanes per instruction, fused multiply-add); chosen at
// run time only on CPUs that have both (ShellForceBatch constructor).
__attribute__((target("avx2,fma"))) int kernelAvx2(LaneBlock& b, const double* material,
                                                   const double* reference,
                                                   const KernelShape& shape, bool damped) {
  return damped ? chunkKernel<true>(b, material, reference, nullptr, shape)
                : chunkKernel<false>(b, material, reference, nullptr, shape);
}
__attribute__((target("avx2,fma"))) int referenceAvx2(LaneBlock& b, double* reference,
                                                      const KernelShape& shape) {
  return chunkKernel<false, true>(b, kNoMaterial, reference, reference, shape);
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
      const ShellSectionScales scales = shellSectionScales(el.section());
      chunk.material[0][l] = scales.membrane;
      chunk.material[1][l] = scales.bending;
      chunk.material[2][l] = scales.damping_s;
      chunk.damped = chunk.damped || scales.damping_s != 0.0;
      // D of each point; the metric and curvature fields are the kernel's own (below).
      for (std::size_t p = 0; p < points; ++p) {
        const ShellPointReference& point = el.quadPoint(p).reference;
        for (int v = 0; v < 6; ++v)
          chunk.reference[(p * kPointFields + static_cast<std::size_t>(v)) * W +
                          static_cast<std::size_t>(l)] = point.d[v];
      }
    }
    chunks_.push_back(std::move(chunk));
  }
  // The kernel's shape data (see KernelShape): C of this element size, and per point the monomial
  // derivatives ∂_k m_i = (2/a)^α (2/b)^β ∂ξ^α ∂η^β (ξ^p η^q) in gather order.
  const ShellMonomialMatrix coefficients = shellMonomialCoefficients(table_->a_m, table_->b_m);
  transform_.resize(kTransformTermCount);
  for (int t = 0; t < kTransformTermCount; ++t) {
    const auto& term = kTransformTerms.terms[t];  // row = monomial, col = node
    transform_[static_cast<std::size_t>(t)] = coefficients[term.col][term.row];
  }
  // ∂^α (s^p)/∂s^α at s.
  const auto derivative = [](int power, int order, double s) {
    double v = 1.0;
    for (int o = 0; o < order; ++o) v *= power - o;
    for (int e = 0; e < power - order; ++e) v *= s;
    return v;
  };
  const double dx = 2.0 / table_->a_m, dy = 2.0 / table_->b_m;  // dξ/dx, dη/dy
  MASTROM_ASSERT(table_->points.size() == points);
  field_terms_.resize(points * kFieldTermCount);
  for (std::size_t p = 0; p < points; ++p) {
    const double xi = table_->points[p][0], eta = table_->points[p][1];
    for (int t = 0; t < kFieldTermCount; ++t) {
      const auto& term = kFieldTerms.terms[t];  // row = field, col = monomial
      const int alpha = kFieldXiOrder[term.row], beta = kFieldEtaOrder[term.row];
      double scale = 1.0;
      for (int o = 0; o < alpha; ++o) scale *= dx;
      for (int o = 0; o < beta; ++o) scale *= dy;
      field_terms_[p * kFieldTermCount + static_cast<std::size_t>(t)] =
          scale * derivative(kShellMonomialXiPower[term.col], alpha, xi) *
          derivative(kShellMonomialEtaPower[term.col], beta, eta);
    }
  }
  use_avx2_ = cpuHasAvx2Fma();
  // The reference metric and curvature of every lane from its e₀ through the kernel that will
  // subtract them (the elements' own values differ from these by round-off of the other path).
  const KernelShape shape{points, field_terms_.data(), transform_.data()};
  for (Chunk& chunk : chunks_) {
    LaneBlock b;
    for (int l = 0; l < W; ++l) {
      const std::size_t k =
          static_cast<std::size_t>(chunk.first_element + (l < chunk.lanes ? l : 0));
      const Vec36& e0 = elements[k]->referenceCoordinates();
      for (int j = 0; j < 12; ++j)
        for (int c = 0; c < 3; ++c) b.x[j][c][l] = e0[3 * j + c];
    }
    int bad = -1;
#if MASTROM_HAVE_AVX2_KERNELS
    if (use_avx2_)
      bad = referenceAvx2(b, chunk.reference.data(), shape);
    else
#endif
      bad = referenceBaseline(b, chunk.reference.data(), shape);
    MASTROM_REQUIRE(bad < 0, InputError, "shell element ", chunk.first_element + bad,
                    ": degenerate reference surface");
  }
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
  const KernelShape shape{table_->derivatives.size(), field_terms_.data(), transform_.data()};
  int bad = -1;
#if MASTROM_HAVE_AVX2_KERNELS
  if (use_avx2_)
    bad = kernelAvx2(b, material, chunk.reference.data(), shape, damped);
  else
#endif
    bad = kernelBaseline(b, material, chunk.reference.data(), shape, damped);
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
