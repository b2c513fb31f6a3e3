// The Schur-complement solver of [M Gᵀ; G 0] (fullorder/mass_saddle_solver.hpp) against a dense LU
// of the same matrix, on the eliminated Scheme 2 mast at a deformed state, and its two refusals: a
// mass matrix that is not positive definite and redundant constraints.
#include <gtest/gtest.h>

#include <Eigen/Dense>  // LU and the symmetric eigensolver
#include <cstdio>
#include <random>

#include "assembly_test_helpers.hpp"
#include "common/error.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/mass_saddle_solver.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {
namespace {

TEST(MassSaddleSolver, AgreesWithADenseLuOfTheSaddleMatrix) {
  MastParameters p;
  p.modules = 3;
  MastModel mast = buildMast(p);
  EliminatedSystem reduced(mast.system());
  const int n = reduced.dofCount(), m = reduced.constraintCount();
  std::mt19937 gen(77);
  const Eigen::VectorXd q =
      reduced.restrict(mast.rotatedReference(0.6)) + testing::randomVector(gen, n, 1e-4);
  SparseMatrix g;
  reduced.constraintJacobian(q, 1.0, g);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + m, n + m);
  a.topLeftCorner(n, n) = Eigen::MatrixXd(reduced.massMatrix());
  a.bottomLeftCorner(m, n) = Eigen::MatrixXd(g);
  a.topRightCorner(n, m) = Eigen::MatrixXd(g).transpose();

  MassSaddleSolver solver(reduced.massMatrix());
  ASSERT_TRUE(solver.positiveDefinite());
  EXPECT_TRUE(solver.perComponentMass());  // the NCF/ANCF mass is M̄ ⊗ I₃
  solver.setConstraintJacobian(g, 1.0);
  // Right-hand sides of the recovery's sizes: forces ~10³ N, constraint terms ~10² m/s².
  Eigen::VectorXd b(n + m);
  b.head(n) = testing::randomVector(gen, n, 1e3);
  b.tail(m) = testing::randomVector(gen, m, 1e2);
  Eigen::VectorXd x;
  const Eigen::VectorXd reference = a.partialPivLu().solve(b);
  // A is symmetric, so its singular values are |eigenvalues| (a symmetric eigensolver compiles in
  // a fraction of an SVD's time).
  const Eigen::VectorXd sigma =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a, Eigen::EigenvaluesOnly).eigenvalues().cwiseAbs();
  const double kappa = sigma.maxCoeff() / sigma.minCoeff();
  const double a_norm = a.cwiseAbs().rowwise().sum().maxCoeff();
  constexpr double kEps = 2.220446049250313e-16;
  for (int call = 0; call < 2; ++call) {  // the second call runs on the work space of the first
    solver.solve(b, x);
    // Normwise backward error |Ax − b| / (|A||x| + |b|): the Schur route is backward stable here
    // like the LU (measured 1.8e-17 against the LU's 6e-18); bound: 64 ulps.
    const double backward = (a * x - b).cwiseAbs().maxCoeff() /
                            (a_norm * x.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff());
    EXPECT_LT(backward, 64 * kEps);
    // Forward error then follows from the conditioning (κ(A) ≈ 5e9: masses of positions against
    // those of slopes): |x − x_LU| ≤ 64 ε κ |x| (measured 1.5e-8 relative).
    EXPECT_LT((x - reference).cwiseAbs().maxCoeff(),
              64 * kEps * kappa * reference.cwiseAbs().maxCoeff());
    if (call == 0)
      std::printf("[ measured ] kappa(A) %.2e, backward error %.2e, |x - x_LU| / |x_LU| %.2e\n",
                  kappa, backward,
                  (x - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff());
  }
}

TEST(MassSaddleSolver, RefusesAnIndefiniteMassAndRedundantConstraints) {
  Eigen::SparseMatrix<double> singular(3, 3);
  singular.insert(0, 0) = 1.0;
  singular.insert(1, 1) = 2.0;  // (2, 2) = 0: semi-definite
  singular.makeCompressed();
  MassSaddleSolver semi(singular);
  EXPECT_FALSE(semi.positiveDefinite());
  SparseMatrix g(1, 3);
  g.insert(0, 0) = 1.0;
  EXPECT_THROW(semi.setConstraintJacobian(g, 0.0), Error);

  Eigen::SparseMatrix<double> mass(3, 3);
  for (int i = 0; i < 3; ++i) mass.insert(i, i) = 1.0 + i;
  MassSaddleSolver solver(mass);
  ASSERT_TRUE(solver.positiveDefinite());
  SparseMatrix twice(2, 3);  // the same equation twice
  twice.insert(0, 1) = 1.0;
  twice.insert(1, 1) = 1.0;
  EXPECT_THROW(solver.setConstraintJacobian(twice, 0.25), NumericalError);
}

}  // namespace
}  // namespace mastrom::fullorder

namespace mastrom::fullorder {
namespace {

// A mass matrix that is not M̄ ⊗ I₃ (the mast's is) takes the general path: same answer.
TEST(MassSaddleSolver, SolvesWithAMassThatIsNotPerComponent) {
  Eigen::SparseMatrix<double> mass(3, 3);
  mass.insert(0, 0) = 2.0;
  mass.insert(1, 1) = 3.0;
  mass.insert(2, 2) = 4.0;
  mass.insert(0, 1) = 0.5;
  mass.insert(1, 0) = 0.5;
  SparseMatrix g(1, 3);
  g.insert(0, 0) = 1.0;
  g.insert(0, 2) = -2.0;
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  a.topLeftCorner<3, 3>() = Eigen::MatrixXd(mass);
  a.bottomLeftCorner<1, 3>() = Eigen::MatrixXd(g);
  a.topRightCorner<3, 1>() = Eigen::MatrixXd(g).transpose();
  MassSaddleSolver solver(mass);
  ASSERT_TRUE(solver.positiveDefinite());
  EXPECT_FALSE(solver.perComponentMass());
  solver.setConstraintJacobian(g, 0.0);
  const Eigen::VectorXd b = Eigen::Vector4d(1.0, -2.0, 0.5, 3.0);
  Eigen::VectorXd x;
  solver.solve(b, x);
  const Eigen::Vector4d reference = a.partialPivLu().solve(Eigen::Vector4d(b));
  EXPECT_LT((x - reference).cwiseAbs().maxCoeff(), 1e-14 * reference.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace mastrom::fullorder
