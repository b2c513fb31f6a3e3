// The mast's default shell quadrature (4×4, fullorder/mast_model.hpp) against 5×5: the modes a
// deployment excites must not notice the difference (docs/theory.md §2.2: "state the order and show
// it is sufficient").
#include <gtest/gtest.h>

#include "fullorder/mast_config.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"

namespace mastrom::modes {
namespace {

Eigen::VectorXd lowestFrequencies(int gauss_order, int modules, int count) {
  Config c;
  c.mast.modules = modules;
  fullorder::MastParameters p = fullorder::mastParametersFromConfig(c);
  p.gauss_order = gauss_order;
  const fullorder::MastModel m = buildLockedMast(p, 0.0);
  Linearization lin = linearizeMast(m);
  EigenSolverOptions o;
  o.count = count;
  o.backend = EigenBackendKind::Dense;
  const EigenResult r = solveConstrainedEigenproblem(lin.problem, o);
  EXPECT_TRUE(r.ok()) << r.message;
  return r.frequencies_hz;
}

TEST(QuadratureOrder, FourByFourMatchesFiveByFiveOnTheMastModes) {
  // Scheme 1, default 2 × 8 mesh: the six lowest modes (bending pair, torsion, axial, rocking
  // pair) measured at |Δf/f| ≤ 1.7e-7; assert 1e-6.
  const Eigen::VectorXd f4 = lowestFrequencies(4, 2, 6), f5 = lowestFrequencies(5, 2, 6);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(f4[i], f5[i], 1e-6 * f5[i]) << "mode " << i;
  // 3 × 3 is visibly worse (2e-4 on the bending pair): the test can tell the orders apart.
  const Eigen::VectorXd f3 = lowestFrequencies(3, 2, 6);
  EXPECT_GT(std::abs(f3[0] - f5[0]), 1e-5 * f5[0]);
}

}  // namespace
}  // namespace mastrom::modes
