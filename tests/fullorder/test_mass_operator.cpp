// MassOperator (fullorder/mass_operator.hpp): M x and y − M x on xyz triples equal the sparse
// product with M, for the eliminated mast's mass (M = M̄ ⊗ I₃, recognised) and for a mass that
// couples components (not recognised, applied as it is).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "assembly_test_helpers.hpp"
#include "coarse_mast.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/mass_operator.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {
namespace {

void expectProductsOf(const SparseMatrix& mass, bool per_component) {
  const MassOperator op(mass);
  EXPECT_EQ(op.perComponent(), per_component);
  std::mt19937 gen(9);
  const Eigen::VectorXd x = testing::randomVector(gen, static_cast<int>(mass.cols()), 2.0);
  const Eigen::VectorXd y0 = testing::randomVector(gen, static_cast<int>(mass.rows()), 1.0);
  const Eigen::VectorXd reference = mass * x;
  const double scale = reference.cwiseAbs().maxCoeff();
  Eigen::VectorXd y(mass.rows());
  op.apply(x, y);
  // Sums in another order: equal to a few ulps of the largest product.
  EXPECT_LT((y - reference).cwiseAbs().maxCoeff(), 1e-14 * scale);
  y = y0;
  op.subtract(x, y);
  EXPECT_LT((y - (y0 - reference)).cwiseAbs().maxCoeff(), 1e-14 * scale);
}

TEST(MassOperator, AppliesTheMastMassOnTriples) {
  MastModel mast = buildMast(mastParametersFromConfig(testing::coarseScheme1()));
  EliminatedSystem reduced(mast.system());
  expectProductsOf(reduced.massMatrix(), true);
  expectProductsOf(mast.system().massMatrix(), true);
}

TEST(MassOperator, AppliesAComponentCouplingMassAsItIs) {
  MastModel mast = buildMast(mastParametersFromConfig(testing::coarseScheme1()));
  SparseMatrix mass = mast.system().massMatrix();
  mass.coeffRef(0, 1) += 1e-3;  // x of coordinate 0 coupled to y of coordinate 1
  mass.coeffRef(1, 0) += 1e-3;
  expectProductsOf(mass, false);
}

}  // namespace
}  // namespace mastrom::fullorder
