// MAC matrix (modes/modal_quantities.hpp).
#include "modes/modal_quantities.hpp"

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "modes/eigen_solver.hpp"
#include "tests/modes/test_models.hpp"

namespace mastrom::modes {
namespace {

EigenResult towerModes(EigenBackendKind backend) {
  EigenSolverOptions options;
  options.backend = backend;
  options.count = 8;
  return solveConstrainedEigenproblem(test_models::latticeTower(6), options);
}

TEST(ModalAssuranceCriterion, MassOrthonormalSetWithItselfIsIdentity) {
  const ConstrainedEigenproblem problem = test_models::latticeTower(6);
  const EigenResult modes = towerModes(EigenBackendKind::Dense);
  ASSERT_TRUE(modes.ok()) << modes.message;
  const Eigen::MatrixXd mac = modalAssuranceCriterion(modes.modes, modes.modes, problem.mass);
  EXPECT_LE((mac - Eigen::MatrixXd::Identity(8, 8)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ModalAssuranceCriterion, InvariantToSignAndScaleOfEachMode) {
  const ConstrainedEigenproblem problem = test_models::latticeTower(6);
  const EigenResult modes = towerModes(EigenBackendKind::Dense);
  ASSERT_TRUE(modes.ok()) << modes.message;
  Eigen::VectorXd factors(8);
  factors << -3.0, 2.0, -0.5, 7.0, 1e-3, -1e4, 1.0, -1.0;
  const Eigen::MatrixXd scaled = modes.modes * factors.asDiagonal();
  // An arbitrary (non-orthonormal) second set, so that off-diagonal entries are non-trivial.
  Eigen::MatrixXd mixed = modes.modes;
  mixed.col(0) += 0.3 * modes.modes.col(1);
  mixed.col(5) -= 2.0 * modes.modes.col(2);
  const Eigen::MatrixXd reference = modalAssuranceCriterion(modes.modes, mixed, problem.mass);
  const Eigen::MatrixXd mac = modalAssuranceCriterion(scaled, -4.0 * mixed, problem.mass);
  EXPECT_LE((mac - reference).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(reference(0, 0), 1.0 / (1.0 + 0.09), 1e-12);  // φ₀ vs φ₀ + 0.3 φ₁, M-orthonormal φ
  EXPECT_NEAR(reference(1, 0), 0.09 / (1.0 + 0.09), 1e-12);
  const Eigen::MatrixXd unweighted = modalAssuranceCriterion(scaled, -4.0 * mixed);
  EXPECT_LE((unweighted - modalAssuranceCriterion(modes.modes, mixed)).cwiseAbs().maxCoeff(),
            1e-12);
  EXPECT_TRUE((unweighted.array() >= 0.0).all() && (unweighted.array() <= 1.0 + 1e-14).all());
}

TEST(ModalAssuranceCriterion, UnweightedSetWithItselfHasUnitDiagonalAndIsSymmetric) {
  const EigenResult modes = towerModes(EigenBackendKind::Dense);
  ASSERT_TRUE(modes.ok()) << modes.message;
  const Eigen::MatrixXd mac = modalAssuranceCriterion(modes.modes, modes.modes);
  EXPECT_LE((mac.diagonal().array() - 1.0).abs().maxCoeff(), 1e-14);
  EXPECT_LE((mac - mac.transpose()).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(ModalAssuranceCriterion, BackendsGiveTheSameShapes) {
  const ConstrainedEigenproblem problem = test_models::latticeTower(6);
  const EigenResult dense = towerModes(EigenBackendKind::Dense);
  const EigenResult arpack = towerModes(EigenBackendKind::Arpack);
  ASSERT_TRUE(dense.ok() && arpack.ok()) << dense.message << " / " << arpack.message;
  const Eigen::MatrixXd mac = modalAssuranceCriterion(dense.modes, arpack.modes, problem.mass);
  EXPECT_LE((mac - Eigen::MatrixXd::Identity(8, 8)).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(ModalAssuranceCriterion, RejectsMismatchedSizesAndZeroModes) {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(5, 2);
  const Eigen::MatrixXd b = Eigen::MatrixXd::Random(6, 2);
  EXPECT_THROW(modalAssuranceCriterion(a, b), InputError);
  SparseMatrix mass(6, 6);
  mass.setIdentity();
  EXPECT_THROW(modalAssuranceCriterion(a, a, mass), InputError);
  Eigen::MatrixXd zero = a;
  zero.col(1).setZero();
  EXPECT_THROW(modalAssuranceCriterion(zero, a), InputError);
}

}  // namespace
}  // namespace mastrom::modes
