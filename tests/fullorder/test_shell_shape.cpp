// Shape functions of the ANCF shell (docs/theory.md §2.2): interpolation property, partition of
// unity, completeness, derivatives against central differences; Gauss rules against exact
// integrals.
#include <cmath>

#include <gtest/gtest.h>

#include "fullorder/gauss_quadrature.hpp"
#include "fullorder/shell_shape.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kA = 0.03, kB = 0.02;  // element sides [m]

TEST(ShellShape, InterpolatesPositionAndBothSlopesAtCorners) {
  for (int i = 0; i < 4; ++i) {
    const ShellShapeValues s = evaluateShellShape(kCornerXi[i], kCornerEta[i], kA, kB);
    for (int k = 0; k < 12; ++k) {
      const int corner = k / 3, kind = k % 3;
      const bool mine = corner == i;
      EXPECT_NEAR(s.n[k], (mine && kind == 0) ? 1.0 : 0.0, 1e-14) << "corner " << i << " k " << k;
      EXPECT_NEAR(s.nx[k], (mine && kind == 1) ? 1.0 : 0.0, 1e-12) << "corner " << i << " k " << k;
      EXPECT_NEAR(s.ny[k], (mine && kind == 2) ? 1.0 : 0.0, 1e-12) << "corner " << i << " k " << k;
    }
  }
}

TEST(ShellShape, PartitionOfUnityAndLinearCompleteness) {
  for (double xi : {-1.0, -0.6, 0.1, 0.77, 1.0}) {
    for (double eta : {-1.0, -0.3, 0.45, 1.0}) {
      const ShellShapeValues s = evaluateShellShape(xi, eta, kA, kB);
      double sum = 0, x = 0, y = 0;
      for (int i = 0; i < 4; ++i) {
        const double xi_corner = 0.5 * kA * (1 + kCornerXi[i]);
        const double yi_corner = 0.5 * kB * (1 + kCornerEta[i]);
        sum += s.n[3 * i];
        // Nodal data of the fields x and y: position value, slope (1,0) resp. (0,1).
        x += s.n[3 * i] * xi_corner + s.n[3 * i + 1];
        y += s.n[3 * i] * yi_corner + s.n[3 * i + 2];
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
      EXPECT_NEAR(x, 0.5 * kA * (1 + xi), 1e-15);
      EXPECT_NEAR(y, 0.5 * kB * (1 + eta), 1e-15);
    }
  }
}

TEST(ShellShape, DerivativesMatchCentralDifferences) {
  // Central difference error ~ h²·f''' with f''' ~ 1/a³: h = 1e-5·a gives ~1e-10 relative to the
  // derivative scale, and round-off ~ ε/h ~ 1e-11; assert 1e-7 relative to each scale.
  const double hx = 1e-5 * kA, hy = 1e-5 * kB;
  for (double xi : {-0.8, 0.2, 0.9}) {
    for (double eta : {-0.5, 0.35}) {
      const ShellShapeValues s = evaluateShellShape(xi, eta, kA, kB);
      const double dxi = 2 * hx / kA, deta = 2 * hy / kB;
      const ShellShapeValues xp = evaluateShellShape(xi + dxi, eta, kA, kB);
      const ShellShapeValues xm = evaluateShellShape(xi - dxi, eta, kA, kB);
      const ShellShapeValues yp = evaluateShellShape(xi, eta + deta, kA, kB);
      const ShellShapeValues ym = evaluateShellShape(xi, eta - deta, kA, kB);
      for (int k = 0; k < 12; ++k) {
        EXPECT_NEAR(s.nx[k], (xp.n[k] - xm.n[k]) / (2 * hx), 1e-7 / kA);
        EXPECT_NEAR(s.ny[k], (yp.n[k] - ym.n[k]) / (2 * hy), 1e-7 / kB);
        EXPECT_NEAR(s.nxx[k], (xp.nx[k] - xm.nx[k]) / (2 * hx), 1e-6 / (kA * kA));
        EXPECT_NEAR(s.nyy[k], (yp.ny[k] - ym.ny[k]) / (2 * hy), 1e-6 / (kB * kB));
        EXPECT_NEAR(s.nxy[k], (yp.nx[k] - ym.nx[k]) / (2 * hy), 1e-6 / (kA * kB));
        EXPECT_NEAR(s.nxy[k], (xp.ny[k] - xm.ny[k]) / (2 * hx), 1e-6 / (kA * kB));
      }
    }
  }
}

TEST(GaussLegendre, IntegratesPolynomialsOfDegreeTwoNMinusOneExactly) {
  for (int n = 1; n <= 8; ++n) {
    const GaussRule rule = gaussLegendre(n);
    for (int p = 0; p <= 2 * n - 1; ++p) {
      double sum = 0;
      for (int i = 0; i < n; ++i) sum += rule.weights[i] * std::pow(rule.points[i], p);
      const double exact = (p % 2 == 1) ? 0.0 : 2.0 / (p + 1);
      EXPECT_NEAR(sum, exact, 1e-14) << "n = " << n << ", degree " << p;
    }
    // And not degree 2n (so the rule really is the n-point one).
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += rule.weights[i] * std::pow(rule.points[i], 2 * n);
    EXPECT_GT(std::abs(sum - 2.0 / (2 * n + 1)), 1e-6) << "n = " << n;
  }
}

}  // namespace
}  // namespace mastrom::fullorder
