// Adini–Clough–Melosh incomplete bicubic functions and their derivatives (docs/theory.md §2.2).
// With s = ξ_i ξ and t = η_i η for corner i:
//   position  N^r = ⅛ (1+s)(1+t)(2 + s + t − ξ² − η²)
//   x-slope   N^x = −a/16 · ξ_i p(s)(1+t),   y-slope  N^y = −b/16 · η_i p(t)(1+s),
// where p(s) = (1+s)²(1−s) = 1 + s − s² − s³. Derivatives are taken in (ξ, η) and mapped to (x, y)
// with ∂/∂x = (2/a) ∂/∂ξ, ∂/∂y = (2/b) ∂/∂η.
#include "fullorder/shell_shape.hpp"

#include "fullorder/gauss_quadrature.hpp"

namespace mastrom::fullorder {
namespace {
inline double cubicP(double s) { return 1.0 + s - s * s - s * s * s; }
inline double cubicDp(double s) { return 1.0 - 2.0 * s - 3.0 * s * s; }
inline double cubicDdp(double s) { return -2.0 - 6.0 * s; }
}  // namespace

ShellShapeValues evaluateShellShape(double xi, double eta, double a_m, double b_m) {
  ShellShapeValues v;
  const double dx = 2.0 / a_m, dy = 2.0 / b_m;  // dξ/dx, dη/dy
  for (int i = 0; i < 4; ++i) {
    const double xi_i = kCornerXi[i], eta_i = kCornerEta[i];
    const double s = xi_i * xi, t = eta_i * eta;
    const int kr = 3 * i, kx = 3 * i + 1, ky = 3 * i + 2;

    // Position function.
    const double g = 2.0 + s + t - xi * xi - eta * eta;
    v.n[kr] = 0.125 * (1 + s) * (1 + t) * g;
    const double r_xi = 0.125 * (xi_i * (1 + t) * g + (1 + s) * (1 + t) * (xi_i - 2 * xi));
    const double r_eta = 0.125 * (eta_i * (1 + s) * g + (1 + s) * (1 + t) * (eta_i - 2 * eta));
    const double r_xixi = -0.75 * s * (1 + t);
    const double r_etaeta = -0.75 * t * (1 + s);
    const double r_xieta = 0.125 * (xi_i * eta_i * g + xi_i * (1 + t) * (eta_i - 2 * eta) +
                                    eta_i * (1 + s) * (xi_i - 2 * xi));

    // x-slope function: −a/16 ξ_i p(s)(1+t).
    const double cx = -a_m / 16.0;
    v.n[kx] = cx * xi_i * cubicP(s) * (1 + t);
    const double x_xi = cx * cubicDp(s) * (1 + t);  // ξ_i² = 1
    const double x_eta = cx * xi_i * cubicP(s) * eta_i;
    const double x_xixi = cx * xi_i * cubicDdp(s) * (1 + t);
    const double x_xieta = cx * cubicDp(s) * eta_i;

    // y-slope function: −b/16 η_i p(t)(1+s).
    const double cy = -b_m / 16.0;
    v.n[ky] = cy * eta_i * cubicP(t) * (1 + s);
    const double y_eta = cy * cubicDp(t) * (1 + s);
    const double y_xi = cy * eta_i * cubicP(t) * xi_i;
    const double y_etaeta = cy * eta_i * cubicDdp(t) * (1 + s);
    const double y_xieta = cy * cubicDp(t) * xi_i;

    v.nx[kr] = dx * r_xi;
    v.ny[kr] = dy * r_eta;
    v.nxx[kr] = dx * dx * r_xixi;
    v.nyy[kr] = dy * dy * r_etaeta;
    v.nxy[kr] = dx * dy * r_xieta;

    v.nx[kx] = dx * x_xi;
    v.ny[kx] = dy * x_eta;
    v.nxx[kx] = dx * dx * x_xixi;
    v.nyy[kx] = 0.0;
    v.nxy[kx] = dx * dy * x_xieta;

    v.nx[ky] = dx * y_xi;
    v.ny[ky] = dy * y_eta;
    v.nxx[ky] = 0.0;
    v.nyy[ky] = dy * dy * y_etaeta;
    v.nxy[ky] = dx * dy * y_xieta;
  }
  return v;
}

std::shared_ptr<const ShellShapeTable> makeShellShapeTable(double a_m, double b_m,
                                                           int gauss_order) {
  const GaussRule rule = gaussLegendre(gauss_order);
  auto table = std::make_shared<ShellShapeTable>();
  table->a_m = a_m;
  table->b_m = b_m;
  table->gauss_order = gauss_order;
  const std::size_t n = rule.points.size();
  table->values.reserve(n * n);
  table->derivatives.reserve(n * n);
  table->weights.reserve(n * n);
  table->points.reserve(n * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      const ShellShapeValues v = evaluateShellShape(rule.points[i], rule.points[j], a_m, b_m);
      Eigen::Matrix<double, 12, 5> d;
      d << v.nx, v.ny, v.nxx, v.nyy, v.nxy;
      table->values.push_back(v);
      table->derivatives.push_back(d);
      table->weights.push_back(rule.weights[i] * rule.weights[j]);
      table->points.push_back({rule.points[i], rule.points[j]});
    }
  }
  return table;
}

}  // namespace mastrom::fullorder
