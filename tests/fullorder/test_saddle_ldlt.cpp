// SaddleLdlt (fullorder/saddle_ldlt.hpp), the LDLᵀ factor of a whole saddle-point matrix:
//  * it solves [A Gᵀ; G 0] like a dense LU (backward stable), reads only A's lower triangle, and
//    refactorises new values on its analysed pattern;
//  * it refuses redundant constraints and an indefinite A, as the Schur complement does;
//  * for a chain its factor grows linearly with the chain — where the Schur complement's dense
//    A⁻¹Gᵀ grows like n·m (the cost it replaces on long masts);
//  * the integrator on that route gives the Schur route's states to within the Newton tolerance,
//    for the iteration matrix and the index-1 recovery alike.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "coarse_mast.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mass_saddle_solver.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/saddle_ldlt.hpp"
#include "spd_test_matrices.hpp"

namespace mastrom::fullorder {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();

/// Constraints along a chain of `nodes` xyz triples: `per_node` rows per node, each on a few
/// coordinates of that node and the next (like the joint and module rows of a mast).
Sparse chainConstraints(int nodes, int per_node, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  const int n = 3 * nodes;
  int row = 0;
  for (int b = 0; b < nodes; ++b)
    for (int r = 0; r < per_node; ++r, ++row)
      for (int k = 0; k < 4; ++k) t.emplace_back(row, (3 * b + 2 * r + k) % n, u(gen));
  Sparse g(row, n);
  g.setFromTriplets(t.begin(), t.end());
  g.makeCompressed();
  return g;
}

Eigen::MatrixXd denseSaddle(const Sparse& a, const Sparse& g) {
  return testing::denseSaddle(Eigen::MatrixXd(a), Eigen::MatrixXd(g));
}

void expectSolvesLikeDenseLu(const SaddleLdlt& ldlt, const Eigen::MatrixXd& h, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd b(h.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = u(gen);
  Eigen::VectorXd x;
  ldlt.solve(b, x);
  const Eigen::VectorXd reference = h.partialPivLu().solve(b);
  const double backward = testing::backwardError(h, x, b);
  // LDLᵀ without pivoting in the constrained order: no growth beyond that of A's Cholesky and of
  // the Schur complement's (the same 64 ε bound as SchurComplement's test).
  EXPECT_LT(backward, 64 * kEps);
  EXPECT_LT((x - reference).cwiseAbs().maxCoeff(), 1e-11 * reference.cwiseAbs().maxCoeff());
}

TEST(SaddleLdlt, SolvesTheSaddleMatrixLikeADenseLu) {
  std::mt19937 gen(21);
  const int nodes = 30;
  const Sparse a = testing::tripleChainSpd(nodes, 2, 12.0, gen);
  const Sparse g = chainConstraints(nodes, 1, gen);
  SaddleLdlt ldlt;
  ASSERT_TRUE(ldlt.compute(a, g));
  EXPECT_EQ(ldlt.size(), a.rows() + g.rows());
  expectSolvesLikeDenseLu(ldlt, denseSaddle(a, g), gen);
}

TEST(SaddleLdlt, ReadsOnlyTheLowerTriangleAndRefactorisesOnItsPattern) {
  std::mt19937 gen(22);
  const int nodes = 12;
  const Sparse a = testing::tripleChainSpd(nodes, 2, 12.0, gen);
  const Sparse g = chainConstraints(nodes, 2, gen);
  // Garbage above the diagonal: not read.
  Sparse spoiled = a;
  for (int j = 0; j < spoiled.outerSize(); ++j)
    for (Sparse::InnerIterator it(spoiled, j); it; ++it)
      if (it.row() < it.col()) it.valueRef() = 1e6;
  SaddleLdlt ldlt;
  ASSERT_TRUE(ldlt.compute(spoiled, g));
  expectSolvesLikeDenseLu(ldlt, denseSaddle(a, g), gen);
  // New values on the same pattern: the analysis is kept, the answer is the new matrix's.
  const Sparse a2 = 2.0 * a;
  const Sparse g2 = -0.5 * g;
  const std::size_t entries = ldlt.factorEntries();
  ASSERT_TRUE(ldlt.compute(a2, g2));
  EXPECT_EQ(ldlt.factorEntries(), entries);
  expectSolvesLikeDenseLu(ldlt, denseSaddle(a2, g2), gen);
  // The symbolic analysis alone gives the factor's size (the route choice reads it before any
  // numeric factorisation, where Eigen's matrixL() asserts).
  SaddleLdlt analysed;
  analysed.analyze(a, g);
  EXPECT_EQ(analysed.factorEntries(), entries);
}

TEST(SaddleLdlt, RefusesRedundantConstraintsAndAnIndefiniteBlock) {
  std::mt19937 gen(23);
  const int n = 30;
  const Sparse a = testing::tripleChainSpd(n / 3, 2, 12.0, gen);
  Eigen::MatrixXd g_dense = Eigen::MatrixXd::Zero(3, n);
  g_dense(0, 1) = 1.0;
  g_dense(1, 4) = 2.0;
  g_dense.row(2) = 0.5 * g_dense.row(0) - g_dense.row(1);  // dependent
  SaddleLdlt ldlt;
  EXPECT_FALSE(ldlt.compute(a, g_dense.sparseView()));
  EXPECT_FALSE(ldlt.ready());
  // An indefinite A (one negative eigenvalue far from the constraints' coordinates).
  Sparse indefinite = a;
  indefinite.coeffRef(20, 20) = -50.0;
  g_dense.row(2).setZero();
  g_dense(2, 7) = 1.0;
  EXPECT_FALSE(ldlt.compute(indefinite, g_dense.sparseView()));
  EXPECT_TRUE(ldlt.compute(a, g_dense.sparseView()));
}

TEST(SaddleLdlt, FactorGrowsLinearlyAlongAChain) {
  // The dense A⁻¹Gᵀ of the Schur route has n·m entries: 4× for a chain twice as long. The LDLᵀ
  // factor of the whole matrix, ordered as SaddleLdlt orders it, stays banded: 2× (the chain's
  // two ends make it a little less).
  std::mt19937 gen(24);
  std::vector<std::size_t> entries;
  for (int nodes : {40, 80, 160}) {
    const Sparse a = testing::tripleChainSpd(nodes, 3, 20.0, gen);
    const Sparse g = chainConstraints(nodes, 1, gen);
    SaddleLdlt ldlt;
    ASSERT_TRUE(ldlt.compute(a, g));
    entries.push_back(ldlt.factorEntries());
  }
  std::printf("[ measured ] factor entries for 40, 80, 160 nodes: %zu, %zu, %zu\n", entries[0],
              entries[1], entries[2]);
  EXPECT_LT(static_cast<double>(entries[1]), 2.2 * static_cast<double>(entries[0]));
  EXPECT_LT(static_cast<double>(entries[2]), 2.2 * static_cast<double>(entries[1]));
}

TEST(SaddleLdlt, MassSaddleSolverOnTheWholeRouteAgreesWithTheSchurRoute) {
  testing::EliminatedTurningMast mast;
  SparseMatrix g;
  mast.reduced.constraintJacobian(mast.q0, 0.0, g);
  MassSaddleSolver schur(mast.reduced.massMatrix(), SaddleRoute::schur_complement),
      whole(mast.reduced.massMatrix(), SaddleRoute::whole_ldlt);
  schur.setConstraintJacobian(g, 0.0);
  whole.setConstraintJacobian(g, 0.0);
  EXPECT_FALSE(schur.solvesWhole());
  EXPECT_TRUE(whole.solvesWhole());
  std::mt19937 gen(25);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd b(g.cols() + g.rows()), x_schur, x_whole;
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = u(gen);
  schur.solve(b, x_schur);
  whole.solve(b, x_whole);
  // Two backward-stable solves of a matrix of condition ~1e6 (masses ~0.1 kg against unit rows).
  EXPECT_LT((x_whole - x_schur).cwiseAbs().maxCoeff(), 1e-9 * x_schur.cwiseAbs().maxCoeff());
}

DaeState runTurningMast(SaddleRoute route, int steps) {
  testing::EliminatedTurningMast mast;
  GeneralizedAlphaOptions o = integratorFromConfig(mast.config);
  o.saddle_route = route;
  GeneralizedAlpha integrator(mast.reduced, o);
  integrator.initialize(mast.q0, mast.v0, 0.0);
  for (int k = 0; k < steps; ++k) integrator.step();
  EXPECT_TRUE(integrator.iterationSolveBySchur());  // the symmetric route, not the LU
  return integrator.state();
}

TEST(SaddleLdlt, TurningMastMatchesTheSchurRoute) {
  // The ramp and 0.02 s of cruise (400 steps of 0.1 ms), as IterationSchur.TurningMastMatchesTheLu.
  const DaeState schur = runTurningMast(SaddleRoute::schur_complement, 400),
                 whole = runTurningMast(SaddleRoute::whole_ldlt, 400);
  const double dq = (whole.q - schur.q).cwiseAbs().maxCoeff();
  const double lambda_peak = schur.lambda_index1.cwiseAbs().maxCoeff();
  const double dlambda = (whole.lambda_index1 - schur.lambda_index1).cwiseAbs().maxCoeff();
  std::printf(
      "[ measured ] whole LDLT vs Schur after 400 steps: |dq| %.2e m, |dlambda|/|lambda| "
      "%.2e\n",
      dq, dlambda / lambda_peak);
  // The same Newton solutions up to the force tolerance, and the recovered multipliers (joint
  // force, torque: the index-1 route's solves) to the 1e-6 relative force criterion. (Recovered
  // accelerations are not compared: the coarse ring's stiffest modes, ω² ~ 1e12 s⁻², turn the
  // 1e-15 m of round-off in q into 1e-3 m/s² of q̈.)
  EXPECT_LT(dq, 1e-10);
  EXPECT_LT(dlambda, 1e-5 * lambda_peak);
}

}  // namespace
}  // namespace mastrom::fullorder
