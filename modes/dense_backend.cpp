// Dense reference backend (docs/theory.md §3): explicit null-space basis of G, reduced symmetric
// pencil, LAPACK-style generalised self-adjoint solver. O(n³) time and O(n²) memory, hence the size
// limit; its value is that it involves no iteration, no shift and no factorisation of the saddle
// system, so it is an independent check of the sparse backends.
//
//   Gᵀ P = Q R (column-pivoted Householder QR), r = rank(G): Z = Q(:, r:n) is an orthonormal basis
//   of null(G); φ = Z y with (ZᵀKZ) y = ω² (ZᵀMZ) y.
#include <Eigen/QR>
#include <algorithm>
#include <numeric>
#include <vector>

#include "common/error.hpp"
#include "modes/eigen_backends.hpp"

namespace mastrom::modes::detail {

RawEigenpairs solveDense(const ConstrainedEigenproblem& problem,
                         const EigenSolverOptions& options) {
  const Eigen::Index n = problem.dofs();
  MASTROM_REQUIRE(n <= kDenseBackendMaxDofs, InputError,
                  "dense eigen-solver backend: the model has ", n,
                  " DOFs, above the dense limit of ", kDenseBackendMaxDofs,
                  " (O(n²) memory, O(n³) time); use backend = \"slepc\" or \"arpack\"");

  // Orthonormal basis of null(G) from the QR factorisation of Gᵀ (n × m).
  Eigen::MatrixXd basis;
  Eigen::Index rank = 0;
  if (problem.constraints() == 0) {
    basis = Eigen::MatrixXd::Identity(n, n);
  } else {
    const Eigen::MatrixXd g_t = Eigen::MatrixXd(problem.constraint_jacobian.transpose());
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(g_t);
    rank = qr.rank();
    basis = Eigen::MatrixXd::Identity(n, n).rightCols(n - rank);
    basis.applyOnTheLeft(qr.householderQ());
  }

  RawEigenpairs raw;
  const Eigen::Index free_dofs = basis.cols();  // ≥ n − m ≥ count (validated by the caller)
  Eigen::MatrixXd work(n, free_dofs);
  Eigen::MatrixXd k_z(free_dofs, free_dofs), m_z(free_dofs, free_dofs);
  work.noalias() = problem.stiffness * basis;
  k_z.noalias() = basis.transpose() * work;
  work.noalias() = problem.mass * basis;
  m_z.noalias() = basis.transpose() * work;
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  if (!symmetricDefiniteEigen(k_z, m_z, values, vectors)) {
    raw.status = EigenStatus::Failed;
    raw.message = "dense: ZᵀMZ is not positive definite (M must be positive definite on null(G))";
    return raw;
  }

  // The `count` eigenvalues nearest σ (the sparse backends' EPS_TARGET_MAGNITUDE / 'LM' of OP).
  std::vector<Eigen::Index> order(static_cast<std::size_t>(free_dofs));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  const double sigma = options.target_rad2_s2;
  std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return std::abs(values(a) - sigma) < std::abs(values(b) - sigma);
  });
  raw.values.resize(options.count);
  raw.vectors.resize(n, options.count);
  for (int j = 0; j < options.count; ++j) {
    const Eigen::Index src = order[static_cast<std::size_t>(j)];
    raw.values(j) = values(src);
    raw.vectors.col(j).noalias() = basis * vectors.col(src);
  }
  raw.status = EigenStatus::Converged;
  raw.message =
      ::mastrom::detail::concat("dense: ", options.count, " of ", free_dofs,
                                " eigenpairs of the null-space problem (rank G = ", rank, ")");
  return raw;
}

}  // namespace mastrom::modes::detail
