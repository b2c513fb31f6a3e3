// Internal to modes/: what each eigen-solver backend implements and the pieces they share.
// Users call solveConstrainedEigenproblem (modes/eigen_solver.hpp), which validates the input,
// dispatches here, and turns the raw pairs into a normalised EigenResult.
#pragma once

#include <string>

#include "modes/eigen_solver.hpp"

namespace mastrom::modes::detail {

/// What a backend hands back: up to `count` pairs nearest σ, in any order and normalisation.
/// Vectors must satisfy G φ = 0 and be linearly independent.
struct RawEigenpairs {
  EigenStatus status = EigenStatus::Failed;
  std::string message;
  int iterations = 0;
  Eigen::VectorXd values;   ///< ω²
  Eigen::MatrixXd vectors;  ///< n × values.size()
};

RawEigenpairs solveDense(const ConstrainedEigenproblem& problem, const EigenSolverOptions& options);
RawEigenpairs solveArpack(const ConstrainedEigenproblem& problem,
                          const EigenSolverOptions& options);
RawEigenpairs solveSlepc(const ConstrainedEigenproblem& problem, const EigenSolverOptions& options);

/// Scale s for the constraint block of the saddle matrix [K − σM, s Gᵀ; s G, 0]: the ratio of the
/// largest diagonal entry of K − σM to the largest |G_ij|. Scaling the constraint rows and the
/// multipliers (μ → μ/s) leaves the eigenpairs unchanged but puts both blocks on the same scale,
/// which the pivoting of the sparse LU factorisations needs (K of a thin shell is ~1e6 … 1e9, G is
/// ~1; cf. Bottasso, Dopico & Trainelli 2008 for the same idea in the integrator).
double constraintScale(const ConstrainedEigenproblem& problem, double sigma);

/// [K − σM, s Gᵀ; s G, 0] with explicit zeros on the (2,2) diagonal (so that factorisations that
/// expect a stored diagonal find one), (n + m) × (n + m), compressed.
SparseMatrix saddleMatrix(const ConstrainedEigenproblem& problem, double sigma, double scale);

/// [M 0; 0 0], (n + m) × (n + m), compressed.
SparseMatrix saddleMassMatrix(const ConstrainedEigenproblem& problem);

/// Dense symmetric-definite pencil a y = λ b y (b symmetric positive definite): values ascending,
/// vectors b-orthonormal. Returns false (outputs unspecified) when the Cholesky factorisation of b
/// fails, i.e. b is not numerically positive definite. (Eigen's GeneralizedSelfAdjointEigenSolver
/// does not report that failure, hence this wrapper.) Only the lower triangles of a and b are read.
bool symmetricDefiniteEigen(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                            Eigen::VectorXd& values, Eigen::MatrixXd& vectors);

/// Krylov subspace size: options.subspace_dimension if set, else max(2·count + 1, 20); capped at
/// the dimension `dim` of the space the iteration lives in.
int subspaceDimension(const EigenSolverOptions& options, Eigen::Index dim);

}  // namespace mastrom::modes::detail
