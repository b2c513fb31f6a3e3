// SupernodalCholesky (fullorder/supernodal_cholesky.hpp) against dense Cholesky solves of the same
// matrices: a 2-D Laplacian (many small supernodes) and a matrix of dense 3 × 3-coupled blocks like
// the iteration matrix's (1,1) block (wide supernodes); refactorisation with new values on the
// analysed pattern; only the lower triangle is read; an indefinite matrix is refused.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <limits>
#include <random>
#include <vector>

#include "fullorder/supernodal_cholesky.hpp"
#include "spd_test_matrices.hpp"

namespace mastrom::fullorder {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();

/// 5-point Laplacian on a k × k grid plus `shift` on the diagonal (SPD for shift ≥ 0).
Sparse laplacian(int k, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  const auto id = [k](int i, int j) { return i * k + j; };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.0 + shift);
      if (i > 0) t.emplace_back(id(i, j), id(i - 1, j), -1.0);
      if (i + 1 < k) t.emplace_back(id(i, j), id(i + 1, j), -1.0);
      if (j > 0) t.emplace_back(id(i, j), id(i, j - 1), -1.0);
      if (j + 1 < k) t.emplace_back(id(i, j), id(i, j + 1), -1.0);
    }
  Sparse a(k * k, k * k);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

/// Normwise backward error |A x − b|∞ / (|A|∞ |x|∞ + |b|∞).
double backwardError(const Sparse& a, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  const double a_norm = Eigen::MatrixXd(a).cwiseAbs().rowwise().sum().maxCoeff();
  return (a * x - b).cwiseAbs().maxCoeff() /
         (a_norm * x.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff());
}

void expectSolvesLikeDenseCholesky(const Sparse& a, std::mt19937& gen) {
  SupernodalCholesky chol;
  ASSERT_TRUE(chol.compute(a));
  ASSERT_TRUE(chol.ready());
  EXPECT_EQ(chol.size(), a.rows());
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd b(a.rows());
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = u(gen);
  const Eigen::VectorXd reference = Eigen::MatrixXd(a).llt().solve(b);
  Eigen::VectorXd x = b;
  chol.solveInPlace(x.data());
  // Cholesky is backward stable: a few ulps times a small growth factor (measured ≤ 2e-17 here).
  EXPECT_LT(backwardError(a, x, b), 16 * kEps);
  // These matrices are well conditioned (κ < 1e3), so the forward error is small too.
  EXPECT_LT((x - reference).cwiseAbs().maxCoeff(), 1e-12 * reference.cwiseAbs().maxCoeff());
}

TEST(SupernodalCholesky, SolvesALaplacianLikeADenseCholesky) {
  std::mt19937 gen(1);
  const Sparse a = laplacian(12, 0.5);
  expectSolvesLikeDenseCholesky(a, gen);
  SupernodalCholesky chol;
  ASSERT_TRUE(chol.compute(a));
  // Every column belongs to exactly one supernode, and the panels hold at least L's entries.
  EXPECT_GT(chol.supernodeCount(), 1);
  EXPECT_LE(chol.supernodeCount(), a.rows());
  EXPECT_GE(chol.panelEntries(), static_cast<std::size_t>(a.rows()));
}

TEST(SupernodalCholesky, GroupsTheColumnsOfDenselyCoupledTriples) {
  std::mt19937 gen(2);
  const Sparse a = testing::tripleChainSpd(30, 3, 20.0, gen);
  expectSolvesLikeDenseCholesky(a, gen);
  SupernodalCholesky chol;
  ASSERT_TRUE(chol.compute(a));
  // The three coordinates of a node share their rows below the diagonal: supernodes are at least
  // three columns wide on average.
  EXPECT_LE(3 * chol.supernodeCount(), a.rows());
}

TEST(SupernodalCholesky, RefactorisesNewValuesOnTheAnalysedPattern) {
  std::mt19937 gen(3);
  Sparse a = testing::tripleChainSpd(20, 3, 20.0, gen);
  SupernodalCholesky chol;
  ASSERT_TRUE(chol.compute(a));
  a.coeffs() *= 3.0;  // same pattern, new values
  a.diagonal().array() += 1.0;
  ASSERT_TRUE(chol.compute(a));
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  Eigen::VectorXd x = b;
  chol.solveInPlace(x.data());
  EXPECT_LT(backwardError(a, x, b), 16 * kEps);
  // A different pattern is analysed anew.
  const Sparse c = laplacian(5, 0.1);
  ASSERT_TRUE(chol.compute(c));
  b = Eigen::VectorXd::Ones(c.rows());
  x = b;
  chol.solveInPlace(x.data());
  EXPECT_LT(backwardError(c, x, b), 16 * kEps);
}

TEST(SupernodalCholesky, ReadsOnlyTheLowerTriangle) {
  std::mt19937 gen(4);
  const Sparse a = testing::tripleChainSpd(10, 3, 20.0, gen);
  Sparse garbled = a;
  for (int j = 0; j < garbled.outerSize(); ++j)
    for (Sparse::InnerIterator it(garbled, j); it; ++it)
      if (it.row() < it.col()) it.valueRef() = 1e6;  // strictly upper
  SupernodalCholesky clean, upper_garbled;
  ASSERT_TRUE(clean.compute(a));
  ASSERT_TRUE(upper_garbled.compute(garbled));
  Eigen::VectorXd x = Eigen::VectorXd::Ones(a.rows()), y = x;
  clean.solveInPlace(x.data());
  upper_garbled.solveInPlace(y.data());
  EXPECT_EQ(x, y);
}

TEST(SupernodalCholesky, RefusesAnIndefiniteMatrix) {
  Sparse a = laplacian(4, 0.0);
  a.coeffRef(5, 5) = -3.0;
  SupernodalCholesky chol;
  EXPECT_FALSE(chol.compute(a));
  EXPECT_FALSE(chol.ready());
  // A later positive definite matrix works again.
  EXPECT_TRUE(chol.compute(laplacian(4, 0.0)));
}

}  // namespace
}  // namespace mastrom::fullorder
