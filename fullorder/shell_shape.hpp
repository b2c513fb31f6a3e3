// Shape functions of the gradient-deficient ANCF thin-shell element (shared/DESIGN.md §2.2).
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

#include <memory>
#include <vector>

#include <Eigen/Core>

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

/// The shape functions at the points of an n × n Gauss rule on an a × b element. They depend on
/// (a, b, n) only, so every element of a structured mesh (all congruent up to a rigid motion) can
/// share one table: 48 elements of the default mast then read one 16-point table that stays in
/// cache instead of 48 copies (DESIGN §2.2; issue #7 "congruent elements share shape data").
struct ShellShapeTable {
  double a_m = 0.0, b_m = 0.0;
  int gauss_order = 0;
  std::vector<ShellShapeValues> values;  ///< point (i, j) of the rule at index i·n + j
  /// Per point, the derivative columns [N_x, N_y, N_xx, N_yy, N_xy] (12×5): Ê·D gives the five
  /// fields g_x, g_y, r_xx, r_yy, r_xy in one product, and C·Dᵀ scatters five force directions
  /// back.
  std::vector<Eigen::Matrix<double, 12, 5>> derivatives;
  std::vector<double> weights;  ///< w_i w_j of the rule on [−1, 1]² (dA = ab/4 · |g_x × g_y| dξ dη)
};

/// Build the table of an a × b element [m] with an n × n rule (1 ≤ n ≤ 20).
std::shared_ptr<const ShellShapeTable> makeShellShapeTable(double a_m, double b_m, int gauss_order);

}  // namespace mastrom::fullorder
