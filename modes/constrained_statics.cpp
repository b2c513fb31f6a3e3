// Constrained static solve (see constrained_statics.hpp).
#include "modes/constrained_statics.hpp"

#include <Eigen/SparseLU>

#include "common/error.hpp"
#include "modes/eigen_backends.hpp"

namespace mastrom::modes {

Eigen::MatrixXd solveConstrainedStatics(const ConstrainedEigenproblem& problem,
                                        const Eigen::MatrixXd& loads) {
  const Eigen::Index n = problem.dofs(), m = problem.constraints();
  MASTROM_REQUIRE(loads.rows() == n, InputError, "constrained statics: ", loads.rows(),
                  " load rows for ", n, " coordinates");
  // The constraint rows scaled to the stiffness (as the shift-invert solvers do): the LU's pivoting
  // then sees entries of one magnitude.
  const double scale = detail::constraintScale(problem, 0.0);
  const SparseMatrix a = detail::saddleMatrix(problem, 0.0, scale);
  Eigen::SparseLU<SparseMatrix> lu;
  lu.compute(a);
  MASTROM_REQUIRE(lu.info() == Eigen::Success, NumericalError,
                  "constrained statics: the saddle matrix [K Gᵀ; G 0] is singular (",
                  lu.lastErrorMessage(), ")");
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n + m, loads.cols());
  rhs.topRows(n) = loads;
  const Eigen::MatrixXd x = lu.solve(rhs);
  MASTROM_REQUIRE(lu.info() == Eigen::Success && x.allFinite(), NumericalError,
                  "constrained statics: the solve failed");
  return x.topRows(n);
}

}  // namespace mastrom::modes
