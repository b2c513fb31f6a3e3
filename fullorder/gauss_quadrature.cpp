#include "fullorder/gauss_quadrature.hpp"

#include <cmath>

#include "common/error.hpp"

namespace mastrom::fullorder {

GaussRule gaussLegendre(int n) {
  MASTROM_REQUIRE(n >= 1 && n <= 20, InputError, "Gauss order = ", n,
                  " is out of range: must be 1..20");
  GaussRule rule;
  rule.points.resize(n);
  rule.weights.resize(n);
  const double pi = std::acos(-1.0);
  for (int i = 0; i < n; ++i) {
    // Chebyshev-like initial guess, then Newton on P_n(x) with the three-term recurrence.
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = (n == 1) ? x : p1;
      const double pnm1 = (n == 1) ? 1.0 : p0;
      dp = n * (x * pn - pnm1) / (x * x - 1.0);
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    rule.points[i] = -x;  // ascending order
    rule.weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return rule;
}

}  // namespace mastrom::fullorder
