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

}  // namespace mastrom::fullorder
