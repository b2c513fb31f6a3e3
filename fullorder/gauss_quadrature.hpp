// Gauss–Legendre rules on [−1, 1] (points and weights), computed once per order by Newton
// iteration on the Legendre polynomial; exact for polynomials of degree 2n − 1.
#pragma once

#include <vector>

namespace mastrom::fullorder {

struct GaussRule {
  std::vector<double> points;
  std::vector<double> weights;
};

/// n-point rule, 1 ≤ n ≤ 20 (InputError otherwise).
GaussRule gaussLegendre(int n);

}  // namespace mastrom::fullorder
