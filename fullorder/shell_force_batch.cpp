// Lane-parallel evaluation of the shell internal force (see the header): the chunks' set-up and the
// choice of the kernel's copy (shell_force_kernel.inc); the point algebra is shellPointForce
// (shell_point_force.hpp), the one every ShellElement force calls.
#include "fullorder/shell_force_batch.hpp"

#include <cmath>
#include <cstring>  // std::memcpy, in the kernel
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

/// The material of the reference pass (read by no line it runs).
constexpr double kNoMaterial[3 * W] = {};

// The kernel, twice (shell_force_kernel.inc). The AVX2 copy is compiled inside a target region, not
// by a target attribute on its entry function alone: the helpers it inlines are then AVX2 functions
// themselves, so the vector types of its sums (Sums3) are AVX2 registers from the start — in a
// helper compiled for the baseline and inlined later they were split and left half scalar.
namespace baseline_isa {
constexpr int kPackLanes = 2;
#include "fullorder/shell_force_kernel.inc"
}  // namespace baseline_isa

#if MASTROM_HAVE_AVX2_KERNELS
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,fma"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2,fma")
#endif
namespace avx2_isa {
constexpr int kPackLanes = 4;
#include "fullorder/shell_force_kernel.inc"
}  // namespace avx2_isa
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
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
      bad = avx2_isa::referenceInvariants(b, chunk.reference.data(), shape);
    else
#endif
      bad = baseline_isa::referenceInvariants(b, chunk.reference.data(), shape);
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
    bad = avx2_isa::chunkForces(b, material, chunk.reference.data(), shape, damped);
  else
#endif
    bad = baseline_isa::chunkForces(b, material, chunk.reference.data(), shape, damped);
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
