// Constrained eigen-solver backends (modes/eigen_solver.hpp) against an analytic answer and against
// each other, with the checks a modal solver owes: projected residuals, M-orthonormality,
// constraint satisfaction; plus the forced failure paths (iteration limit, misuse).
#include "modes/eigen_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "common/error.hpp"
#include "tests/modes/test_models.hpp"

namespace mastrom::modes {
namespace {

using test_models::fixedFreeChain;
using test_models::fixedFreeChainOmegas;
using test_models::latticeTower;

constexpr double kTwoPi = 6.283185307179586;
constexpr double kMassKg = 0.5;
constexpr double kSpringNm = 1.0e4;

EigenSolverOptions optionsFor(EigenBackendKind backend, int count, double target_rad2_s2 = 0.0) {
  EigenSolverOptions options;
  options.backend = backend;
  options.count = count;
  options.target_rad2_s2 = target_rad2_s2;
  return options;
}

/// Residual, orthonormality and constraint checks on every returned pair.
void expectValidModes(const ConstrainedEigenproblem& problem, const EigenResult& result,
                      double residual_tolerance = 1e-8) {
  ASSERT_EQ(result.modes.rows(), problem.dofs());
  ASSERT_EQ(result.modes.cols(), result.converged);
  ASSERT_EQ(result.eigenvalues_rad2_s2.size(), result.converged);
  ASSERT_EQ(result.frequencies_hz.size(), result.converged);
  if (result.converged == 0) return;
  for (int j = 1; j < result.converged; ++j)
    EXPECT_LE(result.eigenvalues_rad2_s2(j - 1), result.eigenvalues_rad2_s2(j))
        << "not ascending at " << j;
  const Eigen::VectorXd residuals = projectedResiduals(problem, result);
  EXPECT_LE(residuals.maxCoeff(), residual_tolerance)
      << "projected residuals " << residuals.transpose();
  Eigen::MatrixXd m_phi(problem.dofs(), result.converged);
  m_phi.noalias() = problem.mass * result.modes;
  Eigen::MatrixXd gram(result.converged, result.converged);
  gram.noalias() = result.modes.transpose() * m_phi;
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(result.converged, result.converged);
  EXPECT_LE((gram - identity).cwiseAbs().maxCoeff(), 1e-10) << "ΦᵀMΦ ≠ I";
  Eigen::MatrixXd g_phi(problem.constraints(), result.converged);
  g_phi.noalias() = problem.constraint_jacobian * result.modes;
  if (problem.constraints() > 0) {
    EXPECT_LE(g_phi.colwise().norm().maxCoeff(), 1e-10) << "‖Gφ‖";
  }
  for (int j = 0; j < result.converged; ++j) {
    const double lambda = result.eigenvalues_rad2_s2(j);
    EXPECT_NEAR(result.frequencies_hz(j),
                std::copysign(std::sqrt(std::abs(lambda)), lambda) / kTwoPi,
                1e-14 * std::abs(result.frequencies_hz(j)));
  }
}

/// Frequencies to `tolerance` relative and shapes entry by entry (both are sign-normalised; only
/// meaningful for simple eigenvalues, which the callers' models have).
void expectSameModes(const EigenResult& reference, const EigenResult& result,
                     double tolerance = 1e-8) {
  ASSERT_EQ(result.converged, reference.converged);
  for (int j = 0; j < result.converged; ++j) {
    EXPECT_NEAR(result.frequencies_hz(j), reference.frequencies_hz(j),
                tolerance * reference.frequencies_hz(j))
        << "mode " << j;
    const double scale = reference.modes.col(j).cwiseAbs().maxCoeff();
    EXPECT_LE((result.modes.col(j) - reference.modes.col(j)).cwiseAbs().maxCoeff(), 1e-6 * scale)
        << "shape of mode " << j;
  }
}

std::string backendName(const ::testing::TestParamInfo<EigenBackendKind>& info) {
  return toString(info.param);
}

// ---------------------------------------------------------------------------------------------------
class EveryBackend : public ::testing::TestWithParam<EigenBackendKind> {};

TEST_P(EveryBackend, FixedFreeChainMatchesAnalyticFrequencies) {
  const int masses = 200;
  const int count = 12;
  const ConstrainedEigenproblem problem = fixedFreeChain(masses, kMassKg, kSpringNm);
  const EigenResult result = solveConstrainedEigenproblem(problem, optionsFor(GetParam(), count));
  ASSERT_EQ(result.status, EigenStatus::Converged) << result.message;
  ASSERT_EQ(result.converged, count);
  EXPECT_EQ(result.backend, GetParam());
  const Eigen::VectorXd exact_hz = fixedFreeChainOmegas(masses, kMassKg, kSpringNm, count) / kTwoPi;
  for (int j = 0; j < count; ++j)
    EXPECT_NEAR(result.frequencies_hz(j), exact_hz(j), 1e-10 * exact_hz(j)) << "mode " << j + 1;
  expectValidModes(problem, result);
}

TEST_P(EveryBackend, LatticeTowerAgreesWithDenseReference) {
  const ConstrainedEigenproblem problem = latticeTower(20);
  const EigenSolverOptions options = optionsFor(GetParam(), 10);
  const EigenResult reference =
      solveConstrainedEigenproblem(problem, optionsFor(EigenBackendKind::Dense, 10));
  const EigenResult result = solveConstrainedEigenproblem(problem, options);
  ASSERT_EQ(reference.status, EigenStatus::Converged) << reference.message;
  ASSERT_EQ(result.status, EigenStatus::Converged) << result.message;
  // The model's lowest modes are simple (the mass spread splits the bending pairs): shapes
  // comparable.
  for (int j = 1; j < 10; ++j)
    ASSERT_GT(reference.eigenvalues_rad2_s2(j) - reference.eigenvalues_rad2_s2(j - 1),
              1e-3 * reference.eigenvalues_rad2_s2(j));
  expectSameModes(reference, result);
  expectValidModes(problem, result);
}

TEST_P(EveryBackend, ShiftedTargetReturnsPairsNearestTarget) {
  const int masses = 200;
  const Eigen::VectorXd omega = fixedFreeChainOmegas(masses, kMassKg, kSpringNm, 40);
  const Eigen::VectorXd lambda = omega.array().square();
  const double sigma =
      0.3 * lambda(19) + 0.7 * lambda(20);  // between the 20th and 21st, nearer the 21st
  const int count = 6;
  const ConstrainedEigenproblem problem = fixedFreeChain(masses, kMassKg, kSpringNm);
  const EigenResult result =
      solveConstrainedEigenproblem(problem, optionsFor(GetParam(), count, sigma));
  ASSERT_EQ(result.status, EigenStatus::Converged) << result.message;
  std::vector<double> nearest(lambda.data(), lambda.data() + lambda.size());
  std::sort(nearest.begin(), nearest.end(),
            [&](double a, double b) { return std::abs(a - sigma) < std::abs(b - sigma); });
  nearest.resize(count);
  std::sort(nearest.begin(), nearest.end());
  ASSERT_EQ(result.converged, count);
  for (int j = 0; j < count; ++j)
    EXPECT_NEAR(result.eigenvalues_rad2_s2(j), nearest[static_cast<std::size_t>(j)],
                1e-10 * nearest[static_cast<std::size_t>(j)]);
  expectValidModes(problem, result);
}

TEST_P(EveryBackend, RepeatedSolvesGiveIdenticalResults) {
  const ConstrainedEigenproblem problem = latticeTower(8);
  const EigenSolverOptions options = optionsFor(GetParam(), 6);
  const EigenResult first = solveConstrainedEigenproblem(problem, options);
  const EigenResult second = solveConstrainedEigenproblem(problem, options);
  ASSERT_EQ(first.status, EigenStatus::Converged) << first.message;
  EXPECT_EQ(first.eigenvalues_rad2_s2, second.eigenvalues_rad2_s2);
  EXPECT_EQ(first.modes, second.modes);
}

TEST_P(EveryBackend, BadSizesAndOptionsAreInputErrors) {
  const ConstrainedEigenproblem good = fixedFreeChain(10, kMassKg, kSpringNm);  // n = 11, m = 1
  const EigenSolverOptions options = optionsFor(GetParam(), 3);

  ConstrainedEigenproblem bad = good;
  bad.mass.resize(10, 10);
  EXPECT_THROW(solveConstrainedEigenproblem(bad, options), InputError);
  bad = good;
  bad.constraint_jacobian.resize(1, 12);
  EXPECT_THROW(solveConstrainedEigenproblem(bad, options), InputError);
  bad = good;
  bad.stiffness.coeffRef(0, 1) += 1.0;  // no longer symmetric
  EXPECT_THROW(solveConstrainedEigenproblem(bad, options), InputError);
  bad = good;
  bad.mass.coeffRef(3, 3) = std::nan("");
  EXPECT_THROW(solveConstrainedEigenproblem(bad, options), InputError);

  EigenSolverOptions wrong = options;
  wrong.count = 0;
  EXPECT_THROW(solveConstrainedEigenproblem(good, wrong), InputError);
  wrong.count = 11;  // n − m = 10
  EXPECT_THROW(solveConstrainedEigenproblem(good, wrong), InputError);
  wrong = options;
  wrong.tolerance = 0.0;
  EXPECT_THROW(solveConstrainedEigenproblem(good, wrong), InputError);
  wrong = options;
  wrong.max_iterations = 0;
  EXPECT_THROW(solveConstrainedEigenproblem(good, wrong), InputError);
  wrong = options;
  wrong.subspace_dimension = 3;  // must exceed count
  EXPECT_THROW(solveConstrainedEigenproblem(good, wrong), InputError);
}

TEST_P(EveryBackend, UnconstrainedFreeFloatingModelWithNegativeShift) {
  // m = 0 and K singular (six rigid-body modes): the classical negative shift σ < 0 keeps K − σM
  // regular; the rigid modes come out at ω² ≈ 0 and the elastic ones as with the dense reference.
  ConstrainedEigenproblem problem = latticeTower(4);
  problem.constraint_jacobian.resize(0, problem.dofs());
  const int count = 9;
  const EigenResult reference =
      solveConstrainedEigenproblem(problem, optionsFor(EigenBackendKind::Dense, count, -1.0));
  const EigenResult result =
      solveConstrainedEigenproblem(problem, optionsFor(GetParam(), count, -1.0));
  ASSERT_EQ(reference.status, EigenStatus::Converged) << reference.message;
  ASSERT_EQ(result.status, EigenStatus::Converged) << result.message;
  const double first_elastic = reference.eigenvalues_rad2_s2(6);
  for (int j = 0; j < 6; ++j)
    EXPECT_LE(std::abs(result.eigenvalues_rad2_s2(j)), 1e-12 * first_elastic);
  for (int j = 6; j < count; ++j)
    EXPECT_NEAR(result.eigenvalues_rad2_s2(j), reference.eigenvalues_rad2_s2(j),
                1e-10 * first_elastic);
  Eigen::MatrixXd m_phi(problem.dofs(), count);
  m_phi.noalias() = problem.mass * result.modes;
  Eigen::MatrixXd gram(count, count);
  gram.noalias() = result.modes.transpose() * m_phi;
  EXPECT_LE((gram - Eigen::MatrixXd::Identity(count, count)).cwiseAbs().maxCoeff(), 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Backends, EveryBackend,
                         ::testing::Values(EigenBackendKind::Dense, EigenBackendKind::Arpack,
                                           EigenBackendKind::Slepc),
                         backendName);

// ---------------------------------------------------------------------------------------------------
class IterativeBackend : public ::testing::TestWithParam<EigenBackendKind> {};

TEST_P(IterativeBackend, IterationLimitIsReportedAsNotConverged) {
  const int masses = 2000;
  const int count = 10;
  const ConstrainedEigenproblem problem = fixedFreeChain(masses, kMassKg, kSpringNm);
  EigenSolverOptions options = optionsFor(GetParam(), count);
  options.max_iterations = 1;
  EigenResult result;
  ASSERT_NO_THROW(result = solveConstrainedEigenproblem(problem, options));
  EXPECT_EQ(result.status, EigenStatus::NotConverged) << result.message;
  EXPECT_FALSE(result.ok());
  EXPECT_LT(result.converged, count);
  EXPECT_FALSE(result.message.empty());
  // What did converge is right: each pair is some exact chain mode, with a small residual.
  const Eigen::VectorXd exact_hz =
      fixedFreeChainOmegas(masses, kMassKg, kSpringNm, masses) / kTwoPi;
  for (int j = 0; j < result.converged; ++j) {
    const double f = result.frequencies_hz(j);
    const double closest = (exact_hz.array() - f).abs().minCoeff();
    EXPECT_LE(closest, 1e-8 * f) << "mode " << j << " at " << f << " Hz is no chain mode";
  }
  expectValidModes(problem, result, 1e-6);
}

TEST_P(IterativeBackend, TwentyThousandDofChain) {
  const int masses = 19999;  // n = 20 000 DOFs, m = 1 constraint
  const int count = 10;
  const ConstrainedEigenproblem problem = fixedFreeChain(masses, kMassKg, kSpringNm);
  const EigenResult result = solveConstrainedEigenproblem(problem, optionsFor(GetParam(), count));
  ASSERT_EQ(result.status, EigenStatus::Converged) << result.message;
  const Eigen::VectorXd exact_hz = fixedFreeChainOmegas(masses, kMassKg, kSpringNm, count) / kTwoPi;
  // The conditioning of the lowest modes grows like N² (λ_max/λ_1 ≈ 6.5e8 here): 1e-8, not 1e-10.
  for (int j = 0; j < count; ++j)
    EXPECT_NEAR(result.frequencies_hz(j), exact_hz(j), 1e-8 * exact_hz(j));
  expectValidModes(problem, result, 1e-6);
  std::cout << "[ timing   ] " << toString(GetParam()) << ": 20 000-DOF chain, " << count
            << " modes in " << result.solve_time_s << " s (" << result.message << ")\n";
}

TEST_P(IterativeBackend, SingularShiftedSaddleMatrixIsReportedAsFailed) {
  // A repeated constraint row makes [K Gᵀ; G 0] singular: the factorisation must fail cleanly, with
  // the factorisation's own diagnosis in one line (no PETSc banner, no exception).
  ConstrainedEigenproblem problem = fixedFreeChain(30, kMassKg, kSpringNm);
  problem.constraint_jacobian.conservativeResize(2, problem.dofs());
  problem.constraint_jacobian.insert(1, 0) = 2.0;
  EigenResult result;
  ASSERT_NO_THROW(result = solveConstrainedEigenproblem(problem, optionsFor(GetParam(), 5)));
  EXPECT_EQ(result.status, EigenStatus::Failed) << result.message;
  EXPECT_EQ(result.converged, 0);
  EXPECT_EQ(result.modes.cols(), 0);
  const char* diagnosis = GetParam() == EigenBackendKind::Arpack ? "SparseLU" : "MUMPS";
  EXPECT_NE(result.message.find(diagnosis), std::string::npos) << result.message;
  EXPECT_EQ(result.message.find('\n'), std::string::npos) << result.message;
}

TEST_P(IterativeBackend, AskingForTheWholeNullSpaceIsFailedWithAdvice) {
  // Krylov methods need count < n − m; the dense backend does not (checked alongside).
  const ConstrainedEigenproblem problem = fixedFreeChain(5, kMassKg, kSpringNm);  // n − m = 5
  const EigenResult dense =
      solveConstrainedEigenproblem(problem, optionsFor(EigenBackendKind::Dense, 5));
  EXPECT_EQ(dense.status, EigenStatus::Converged) << dense.message;
  EigenResult result;
  ASSERT_NO_THROW(result = solveConstrainedEigenproblem(problem, optionsFor(GetParam(), 5)));
  EXPECT_EQ(result.status, EigenStatus::Failed);
  EXPECT_NE(result.message.find("dense backend"), std::string::npos) << result.message;
}

INSTANTIATE_TEST_SUITE_P(Backends, IterativeBackend,
                         ::testing::Values(EigenBackendKind::Arpack, EigenBackendKind::Slepc),
                         backendName);

// ---------------------------------------------------------------------------------------------------
TEST(DenseBackend, RefusesModelsAboveTheSizeLimit) {
  const ConstrainedEigenproblem problem = fixedFreeChain(6000, kMassKg, kSpringNm);  // n = 6001
  try {
    static_cast<void>(
        solveConstrainedEigenproblem(problem, optionsFor(EigenBackendKind::Dense, 4)));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("6001"), std::string::npos) << e.what();
  }
}

TEST(DenseBackend, ToleratesARedundantConstraintRow) {
  // The null-space basis comes from a rank-revealing QR: a repeated row of G changes nothing.
  ConstrainedEigenproblem problem = fixedFreeChain(30, kMassKg, kSpringNm);
  problem.constraint_jacobian.conservativeResize(2, problem.dofs());
  problem.constraint_jacobian.insert(1, 0) = 2.0;
  const EigenResult result =
      solveConstrainedEigenproblem(problem, optionsFor(EigenBackendKind::Dense, 5));
  ASSERT_EQ(result.status, EigenStatus::Converged) << result.message;
  const Eigen::VectorXd exact_hz = fixedFreeChainOmegas(30, kMassKg, kSpringNm, 5) / kTwoPi;
  for (int j = 0; j < 5; ++j)
    EXPECT_NEAR(result.frequencies_hz(j), exact_hz(j), 1e-10 * exact_hz(j));
}

// ---------------------------------------------------------------------------------------------------
// SLEPc on a distributed problem: run by tests/cli/modes_mpi.cmake under `mpirun -n 2` (together
// with Backends/EveryBackend.*/slepc). Every solve is collective, so all solves come before any
// ASSERT.
TEST(SlepcAgainstDense, LatticeTowerWithShift) {
  const ConstrainedEigenproblem problem = latticeTower(12);
  const EigenResult first =
      solveConstrainedEigenproblem(problem, optionsFor(EigenBackendKind::Dense, 4));
  ASSERT_EQ(first.status, EigenStatus::Converged) << first.message;
  const double sigma = 0.5 * (first.eigenvalues_rad2_s2(2) + first.eigenvalues_rad2_s2(3)) * 1.01;
  const EigenResult reference =
      solveConstrainedEigenproblem(problem, optionsFor(EigenBackendKind::Dense, 5, sigma));
  const EigenResult result =
      solveConstrainedEigenproblem(problem, optionsFor(EigenBackendKind::Slepc, 5, sigma));
  ASSERT_EQ(reference.status, EigenStatus::Converged) << reference.message;
  ASSERT_EQ(result.status, EigenStatus::Converged) << result.message;
  expectSameModes(reference, result);
  expectValidModes(problem, result);
}

TEST(SlepcAgainstDense, SelfCommunicatorSolvesPerRank) {
  // MPI_COMM_SELF: every rank solves its own copy (how `rom build` distributes samples).
  const ConstrainedEigenproblem problem = latticeTower(10);
  EigenSolverOptions options = optionsFor(EigenBackendKind::Slepc, 6);
  options.communicator = MPI_COMM_SELF;
  const EigenResult result = solveConstrainedEigenproblem(problem, options);
  const EigenResult reference =
      solveConstrainedEigenproblem(problem, optionsFor(EigenBackendKind::Dense, 6));
  ASSERT_EQ(result.status, EigenStatus::Converged) << result.message;
  EXPECT_NE(result.message.find("1 rank"), std::string::npos) << result.message;
  expectSameModes(reference, result);
  expectValidModes(problem, result);
}

}  // namespace
}  // namespace mastrom::modes
