// The constrained generalised eigenproblem of docs/theory.md §3 and the one entry point that
// solves it with any of the three backends (SLEPc, ARPACK, dense Eigen reference).
//
//     K φ = ω² M φ   subject to   G φ = 0,
//
// K (n×n) symmetric, positive semi-definite on null(G) (it may be indefinite or singular outside
// it); M (n×n) symmetric positive semi-definite and positive definite on null(G); G (m×n) of full
// row rank. Equivalently (the form the sparse backends factor) the saddle-point pencil
//
//     [K  Gᵀ] [φ]        [M  0] [φ]
//     [G  0 ] [μ]  = ω²  [0  0] [μ] ,
//
// whose multipliers μ are not returned. K and M are used as stored: store both triangles (no
// triangle is implied from the other).
//
// Outcome is reported Eigen/Spectra style through EigenResult::status (Converged, NotConverged,
// Failed); only misuse (size mismatch, bad options) throws InputError.
#pragma once

#include <mpi.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

#include "common/kinds.hpp"

namespace mastrom::modes {

using SparseMatrix = Eigen::SparseMatrix<double>;  ///< column-major, int indices

/// The matrices of one constrained eigenproblem (values; move them in to avoid copies).
struct ConstrainedEigenproblem {
  SparseMatrix stiffness;            ///< K, n×n, symmetric (SI units of the model)
  SparseMatrix mass;                 ///< M, n×n, symmetric positive semi-definite
  SparseMatrix constraint_jacobian;  ///< G, m×n, full row rank (m may be 0)

  Eigen::Index dofs() const { return stiffness.rows(); }                   ///< n
  Eigen::Index constraints() const { return constraint_jacobian.rows(); }  ///< m
  /// Throws InputError unless the sizes agree, m < n, every entry is finite and K, M are symmetric
  /// (to 1e-8 of their largest entry).
  void validate() const;
};

/// Largest model the dense reference accepts. It forms n × n dense matrices and computes every
/// eigenvector of the reduced pencil: O(n²) memory, O(n³) time with a large constant (CPU time
/// measured on the 2-core development machine: n = 1000 ≈ 1 s, n = 2000 ≈ 7 s, n = 4000 ≈ 100 s). A
/// paper-size mast has ≈ 10³ unknowns (docs/architecture.md). Above it the dense backend throws
/// InputError.
constexpr Eigen::Index kDenseBackendMaxDofs = 4000;

/// How to solve. Defaults: the 10 modes nearest 0 with SLEPc.
struct EigenSolverOptions {
  int count = 10;               ///< number of eigenpairs wanted, 1 ≤ count ≤ n − m
  double target_rad2_s2 = 0.0;  ///< shift σ [rad²/s²]: the pairs with ω² nearest σ are returned
  double tolerance = 1e-10;     ///< relative residual tolerance of the iterative backends
  int max_iterations = 1000;    ///< restarts (SLEPc) / Arnoldi update iterations (ARPACK)
  int subspace_dimension = 0;  ///< Krylov basis size; 0 = automatic (max(2·count + 1, 20), capped)
  EigenBackendKind backend = EigenBackendKind::Slepc;
  /// SLEPc only: communicator the matrices are distributed over. MPI_COMM_NULL = PETSC_COMM_WORLD
  /// (one eigenproblem shared by all ranks: the call is collective and every rank must pass the
  /// same matrices); MPI_COMM_SELF = every rank solves its own problem. ARPACK and dense always run
  /// serially in the calling process.
  MPI_Comm communicator = MPI_COMM_NULL;

  /// Throws InputError naming the field, value and allowed range.
  void validate() const;
};

/// Outcome of a solve (Eigen's ComputationInfo, with the partial case made explicit).
enum class EigenStatus {
  Converged,     ///< all `count` requested pairs converged
  NotConverged,  ///< iteration limit reached: the pairs that did converge are returned
  Failed  ///< numerical breakdown (singular shifted pencil, bad factorisation, …): no pairs
};
std::string toString(EigenStatus status);

/// Eigenpairs in ascending order of ω², mass-normalised (ΦᵀMΦ = I) and sign-normalised (the first
/// entry whose magnitude is within 1e-6 relative of the largest is positive), so that results of
/// different backends and runs compare entry by entry for simple eigenvalues.
struct EigenResult {
  EigenStatus status = EigenStatus::Failed;
  std::string message;  ///< one line: what happened (always set)
  EigenBackendKind backend = EigenBackendKind::Dense;
  int requested = 0;                    ///< options.count
  int converged = 0;                    ///< number of pairs returned (columns of `modes`)
  int iterations = 0;                   ///< iterations used by the iterative backends (0 for dense)
  Eigen::VectorXd eigenvalues_rad2_s2;  ///< ω², ascending
  /// f = sign(ω²)·√|ω²| / 2π [Hz]: a (numerically) negative ω² gives a negative frequency, so that
  /// an unstable preloaded state or a round-off rigid-body mode is visible rather than hidden.
  Eigen::VectorXd frequencies_hz;
  Eigen::MatrixXd modes;      ///< Φ, n × converged
  double solve_time_s = 0.0;  ///< wall time of the backend call

  EigenStatus info() const { return status; }
  bool ok() const { return status == EigenStatus::Converged; }
};

/// Solve the constrained eigenproblem with options.backend. Throws InputError for invalid problem
/// or options; every numerical outcome (including non-convergence and breakdown) comes back as
/// status. With the SLEPc backend the caller must hold an initialised SLEPc (a SlepcSession, see
/// modes/slepc_session.hpp; otherwise UsageError); on a multi-rank communicator the call is
/// collective.
EigenResult solveConstrainedEigenproblem(const ConstrainedEigenproblem& problem,
                                         const EigenSolverOptions& options);

/// Relative projected residual of each returned pair,
///     ‖P (K φ − ω² M φ)‖ / max(‖K φ‖, |ω²| ‖M φ‖),   P = I − Gᵀ (G Gᵀ)⁻¹ G,
/// the orthogonal projector onto null(G): for the constrained problem K φ − ω² M φ = −Gᵀ μ lies in
/// range(Gᵀ), so its projection vanishes at an exact eigenpair.
Eigen::VectorXd projectedResiduals(const ConstrainedEigenproblem& problem,
                                   const EigenResult& result);

}  // namespace mastrom::modes
