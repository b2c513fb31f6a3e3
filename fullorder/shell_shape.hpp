// Shape functions of the gradient-deficient ANCF thin-shell element (docs/theory.md §2.2).
//
// Four corner nodes, each carrying e_i = [r, ∂r/∂x, ∂r/∂y] ∈ R⁹. The twelve scalar functions are the
// incomplete bicubic Adini–Clough–Melosh set (Dmitrochenko & Pogorelov 2003). Corner numbering in the
// element's reference rectangle a × b (ξ = 2x/a − 1, η = 2y/b − 1):
//
//        y ↑
//   4 (−1,+1) ───── 3 (+1,+1)
//        │             │
//   1 (−1,−1) ───── 2 (+1,−1)  → x
//
// Scalar function index k = 3·i + j for corner i ∈ {0..3} and j ∈ {0: position, 1: x-slope,
// 2: y-slope}; the element vector e ∈ R³⁶ is ordered the same way in blocks of three, so
// r(x, y) = Σ_k N_k(x, y) e_k with e_k the k-th 3-block — i.e. r = Ê N with Ê = e viewed as a 3×12
// column-major matrix.
#pragma once

#include <array>
#include <memory>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "common/error.hpp"

namespace mastrom::fullorder {

using Vec12 = Eigen::Matrix<double, 12, 1>;

/// Values and parameter-coordinate derivatives (w.r.t. x, y in metres, not ξ, η) of the 12 functions.
struct ShellShapeValues {
  Vec12 n;    ///< N_k
  Vec12 nx;   ///< ∂N_k/∂x   [1/m]
  Vec12 ny;   ///< ∂N_k/∂y   [1/m]
  Vec12 nxx;  ///< ∂²N_k/∂x² [1/m²]
  Vec12 nxy;  ///< ∂²N_k/∂x∂y
  Vec12 nyy;  ///< ∂²N_k/∂y²
};

/// Corner signs (ξ_i, η_i) of corner i = 0..3.
constexpr double kCornerXi[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr double kCornerEta[4] = {-1.0, -1.0, 1.0, 1.0};

/// Evaluate the shape functions at (ξ, η) ∈ [−1, 1]² of an a × b element [m].
ShellShapeValues evaluateShellShape(double xi, double eta, double a_m, double b_m);

/// The 12 functions span exactly the 12 monomials ξ^p η^q with these exponents (the complete cubic
/// plus ξ³η and ξη³ — the "incomplete bicubic" of docs/theory.md §2.2): N_k = Σ_i C(k, i) ξ^{p_i}
/// η^{q_i}. Monomial 0 (the constant) is the only one no derivative sees.
constexpr int kShellMonomialXiPower[12] = {0, 1, 0, 2, 1, 0, 3, 2, 1, 0, 3, 1};
constexpr int kShellMonomialEtaPower[12] = {0, 0, 1, 0, 1, 2, 0, 1, 2, 3, 1, 3};

/// C(k, i), row k = shape function, column i = monomial.
using ShellMonomialMatrix = std::array<std::array<double, 12>, 12>;

namespace shell_monomial_detail {
/// Polynomial in (ξ, η) of degree ≤ 3 in each: coefficient of ξ^p η^q at [p][q].
using Poly = std::array<std::array<double, 4>, 4>;
constexpr Poly product(const Poly& u, const Poly& v) {
  Poly r{};
  for (int p = 0; p < 4; ++p)
    for (int q = 0; q < 4; ++q)
      for (int s = 0; s < 4; ++s)
        for (int t = 0; t < 4; ++t)
          if (u[p][q] * v[s][t] != 0.0) {
            if (p + s > 3 || q + t > 3) throw UsageError("shell monomials: degree above 3");
            r[p + s][q + t] += u[p][q] * v[s][t];
          }
  return r;
}
}  // namespace shell_monomial_detail

/// The coefficients C of an a × b element [m], by expanding the formulas of docs/theory.md §2.2.
/// Exact: the products of the small-integer polynomials are exact, and the factors ⅛, 1/16 are
/// powers of two (the slope functions' integer coefficients are ±1). constexpr so that the sparsity
/// pattern (independent of a, b) is known at compile time; a term outside the 12 monomials fails to
/// compile (shellMonomialCoefficients(1, 1) is evaluated in a constant expression by
/// shell_force_batch.cpp), which proves the claim above.
constexpr ShellMonomialMatrix shellMonomialCoefficients(double a_m, double b_m) {
  using shell_monomial_detail::Poly;
  using shell_monomial_detail::product;
  ShellMonomialMatrix c{};
  for (int i = 0; i < 4; ++i) {
    const double si = kCornerXi[i], ti = kCornerEta[i];
    Poly ux{}, uy{}, g{}, px{}, py{};
    ux[0][0] = 1.0, ux[1][0] = si;  // 1 + ξ_i ξ
    uy[0][0] = 1.0, uy[0][1] = ti;  // 1 + η_i η
    g[0][0] = 2.0, g[1][0] = si, g[0][1] = ti, g[2][0] = -1.0, g[0][2] = -1.0;
    // p(ξ_i ξ) = 1 + s − s² − s³ with s = ξ_i ξ (ξ_i² = 1), likewise in η.
    px[0][0] = 1.0, px[1][0] = si, px[2][0] = -1.0, px[3][0] = -si;
    py[0][0] = 1.0, py[0][1] = ti, py[0][2] = -1.0, py[0][3] = -ti;
    const Poly functions[3] = {product(product(ux, uy), g), product(px, uy), product(py, ux)};
    const double scale[3] = {0.125, -a_m / 16.0 * si, -b_m / 16.0 * ti};
    for (int j = 0; j < 3; ++j)
      for (int p = 0; p < 4; ++p)
        for (int q = 0; q < 4; ++q) {
          if (functions[j][p][q] == 0.0) continue;
          int m = 0;
          while (m < 12 && !(kShellMonomialXiPower[m] == p && kShellMonomialEtaPower[m] == q)) ++m;
          if (m == 12) throw UsageError("shell monomials: a term outside the 12 monomials");
          c[3 * i + j][m] = scale[j] * functions[j][p][q];
        }
  }
  return c;
}

/// The shape functions at the points of an n × n Gauss rule on an a × b element. They depend on
/// (a, b, n) only, so every element of a structured mesh (all congruent up to a rigid motion) can
/// share one table: 48 elements of the default mast then read one 16-point table that stays in
/// cache instead of 48 copies (docs/theory.md §2.2).
struct ShellShapeTable {
  double a_m = 0.0, b_m = 0.0;
  int gauss_order = 0;
  std::vector<ShellShapeValues> values;  ///< point (i, j) of the rule at index i·n + j
  /// Per point, the derivative columns [N_x, N_y, N_xx, N_yy, N_xy] (12×5): Ê·D gives the five
  /// fields g_x, g_y, r_xx, r_yy, r_xy in one product, and C·Dᵀ scatters five force directions
  /// back.
  std::vector<Eigen::Matrix<double, 12, 5>> derivatives;
  std::vector<double> weights;  ///< w_i w_j of the rule on [−1, 1]² (dA = ab/4 · |g_x × g_y| dξ dη)
  std::vector<std::array<double, 2>> points;  ///< (ξ, η) of each point
};

/// Build the table of an a × b element [m] with an n × n rule (1 ≤ n ≤ 20).
std::shared_ptr<const ShellShapeTable> makeShellShapeTable(double a_m, double b_m, int gauss_order);

}  // namespace mastrom::fullorder
