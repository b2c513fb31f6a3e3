// Pieces shared by the sparse backends: the (scaled) saddle-point matrices and the Krylov size.
#include "modes/eigen_backends.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

namespace mastrom::modes::detail {

double constraintScale(const ConstrainedEigenproblem& problem, double sigma) {
  double g_max = 0.0;
  const SparseMatrix& g = problem.constraint_jacobian;
  for (Eigen::Index k = 0; k < g.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(g, k); it; ++it)
      g_max = std::max(g_max, std::abs(it.value()));
  if (g_max == 0.0) return 1.0;
  const Eigen::VectorXd diag_k = problem.stiffness.diagonal();
  const Eigen::VectorXd diag_m = problem.mass.diagonal();
  const double d_max = (diag_k - sigma * diag_m).cwiseAbs().maxCoeff();
  return d_max > 0.0 ? d_max / g_max : 1.0;
}

SparseMatrix saddleMatrix(const ConstrainedEigenproblem& problem, double sigma, double scale) {
  const Eigen::Index n = problem.dofs();
  const Eigen::Index m = problem.constraints();
  const SparseMatrix shifted = problem.stiffness - sigma * problem.mass;
  const SparseMatrix& g = problem.constraint_jacobian;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(shifted.nonZeros() + 2 * g.nonZeros() + m));
  for (Eigen::Index k = 0; k < shifted.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(shifted, k); it; ++it)
      entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  for (Eigen::Index k = 0; k < g.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(g, k); it; ++it) {
      const auto row = static_cast<int>(n + it.row());
      const auto col = static_cast<int>(it.col());
      entries.emplace_back(row, col, scale * it.value());
      entries.emplace_back(col, row, scale * it.value());
    }
  for (Eigen::Index i = 0; i < m; ++i)
    entries.emplace_back(static_cast<int>(n + i), static_cast<int>(n + i), 0.0);
  SparseMatrix a(n + m, n + m);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

SparseMatrix saddleMassMatrix(const ConstrainedEigenproblem& problem) {
  const Eigen::Index n = problem.dofs();
  const Eigen::Index size = n + problem.constraints();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(problem.mass.nonZeros()));
  for (Eigen::Index k = 0; k < problem.mass.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(problem.mass, k); it; ++it)
      entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  SparseMatrix b(size, size);
  b.setFromTriplets(entries.begin(), entries.end());
  b.makeCompressed();
  return b;
}

bool symmetricDefiniteEigen(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                            Eigen::VectorXd& values, Eigen::MatrixXd& vectors) {
  // Standard reduction: b = L Lᵀ, C = L⁻¹ a L⁻ᵀ, C v = λ v, y = L⁻ᵀ v.
  const Eigen::LLT<Eigen::MatrixXd> chol(b);
  if (chol.info() != Eigen::Success) return false;
  Eigen::MatrixXd c = a.selfadjointView<Eigen::Lower>();
  chol.matrixL().solveInPlace<Eigen::OnTheLeft>(c);
  chol.matrixU().solveInPlace<Eigen::OnTheRight>(c);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(c, Eigen::ComputeEigenvectors);
  if (eig.info() != Eigen::Success) return false;
  values = eig.eigenvalues();
  vectors = eig.eigenvectors();
  chol.matrixU().solveInPlace(vectors);
  return true;
}

int subspaceDimension(const EigenSolverOptions& options, Eigen::Index dim) {
  const int wanted = options.subspace_dimension > 0 ? options.subspace_dimension
                                                    : std::max(2 * options.count + 1, 20);
  return static_cast<int>(std::min<Eigen::Index>(wanted, dim));
}

}  // namespace mastrom::modes::detail
