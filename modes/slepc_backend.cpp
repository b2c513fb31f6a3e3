// SLEPc backend (docs/theory.md §3): the symmetric-definite saddle pencil
//     A = [K  sGᵀ; sG  0],   B = [M 0; 0 0]        (s: constraintScale, see eigen_backends.hpp)
// as EPS_GHEP, Krylov–Schur, shift-and-invert about σ (STSINVERT) with the nev eigenvalues of
// largest |1/(λ − σ)| (EPS_TARGET_MAGNITUDE), the shifted saddle matrix factored by MUMPS as a
// symmetric indefinite LDLᵀ (PETSc's own factorisations meet zero pivots on the saddle diagonal and
// cannot factor in parallel). B is only
// semidefinite: the infinite eigenvalues of the pencil map to θ = 0 of the shift-invert operator
// and never appear among the wanted ones; Krylov–Schur's eigenvector purification (on by default)
// removes their components from the returned vectors. EPSSetFromOptions is called last, so -eps_* /
// -st_* options on the command line override these defaults.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "common/error.hpp"
#include "modes/eigen_backends.hpp"
#include "modes/petsc_wrap.hpp"

namespace mastrom::modes::detail {
namespace {
/// MUMPS ICNTL(14): percentage increase of the estimated working space (see solveSlepc).
constexpr PetscInt kMumpsWorkspacePercent = 100;
}  // namespace

RawEigenpairs solveSlepc(const ConstrainedEigenproblem& problem,
                         const EigenSolverOptions& options) {
  if (!SlepcSession::active())
    throw UsageError("SLEPc eigen-solver backend called without an active SlepcSession");
  const petsc::QuietErrors quiet;
  const MPI_Comm comm =
      options.communicator == MPI_COMM_NULL ? PETSC_COMM_WORLD : options.communicator;
  const Eigen::Index n = problem.dofs();
  const double sigma = options.target_rad2_s2;

  RawEigenpairs raw;
  const int ncv = subspaceDimension(options, n - problem.constraints());
  if (ncv <=
      options.count) {  // Krylov–Schur needs ncv ≥ nev + 1 inside the (n − m)-dimensional null(G)
    raw.message = ::mastrom::detail::concat(
        "slepc: needs count < n − m, got count = ", options.count,
        ", n − m = ", n - problem.constraints(), "; use the dense backend for such small models");
    return raw;
  }

  const double scale = constraintScale(problem, sigma);
  const petsc::MatOwner a = petsc::toPetscMatrix(saddleMatrix(problem, 0.0, scale), comm);
  const petsc::MatOwner b = petsc::toPetscMatrix(saddleMassMatrix(problem), comm);

  petsc::EpsOwner eps;
  MASTROM_PETSC_CALL(EPSCreate(comm, eps.out()));
  MASTROM_PETSC_CALL(EPSSetOperators(eps.get(), a.get(), b.get()));
  MASTROM_PETSC_CALL(EPSSetProblemType(eps.get(), EPS_GHEP));
  MASTROM_PETSC_CALL(EPSSetType(eps.get(), EPSKRYLOVSCHUR));
  MASTROM_PETSC_CALL(EPSSetDimensions(eps.get(), options.count, ncv, PETSC_DEFAULT));
  MASTROM_PETSC_CALL(EPSSetTarget(eps.get(), sigma));
  MASTROM_PETSC_CALL(EPSSetWhichEigenpairs(eps.get(), EPS_TARGET_MAGNITUDE));
  MASTROM_PETSC_CALL(EPSSetTolerances(eps.get(), options.tolerance, options.max_iterations));
  ST st = nullptr;  // borrowed from eps
  MASTROM_PETSC_CALL(EPSGetST(eps.get(), &st));
  MASTROM_PETSC_CALL(STSetType(st, STSINVERT));
  KSP ksp = nullptr;  // borrowed from st
  MASTROM_PETSC_CALL(STGetKSP(st, &ksp));
  MASTROM_PETSC_CALL(KSPSetType(ksp, KSPPREONLY));
  PC pc = nullptr;  // borrowed from ksp
  MASTROM_PETSC_CALL(KSPGetPC(ksp, &pc));
  MASTROM_PETSC_CALL(PCSetType(pc, PCCHOLESKY));
  MASTROM_PETSC_CALL(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  // The shifted saddle matrix is symmetric indefinite: MUMPS's LDLᵀ with 2 × 2 pivots (PETSc
  // Cholesky of an AIJ matrix = MUMPS SYM = 2) needs half the factor storage and solve work of LU
  // (measured on Scheme 1 at 38 040 DOFs: solve 5.6 s against 9–11 s with LU, same eigenpairs).
  // MUMPS sizes its workspace from the analysis; the saddle matrices of the mast (thousands of
  // bonded-edge rows with zero diagonal) need delayed pivots beyond the default 20 % reserve and
  // otherwise stop with INFOG(1) = −9 (measured on Scheme 2, 468 DOFs). ICNTL(14) = 100 % extra.
  // STGetOperator hands the shifted matrix to the KSP so the factor object exists (SLEPc ex43).
  MASTROM_PETSC_CALL(STGetOperator(st, nullptr));
  MASTROM_PETSC_CALL(PCFactorSetUpMatSolverType(pc));
  Mat factor = nullptr;  // borrowed from pc
  MASTROM_PETSC_CALL(PCFactorGetMatrix(pc, &factor));
  MASTROM_PETSC_CALL(MatMumpsSetIcntl(factor, 14, kMumpsWorkspacePercent));
  // LDLᵀ does not stop at a singular matrix the way LU does (INFOG(1) = −10); null-pivot detection
  // (ICNTL(24) = 1) counts the zero pivots in INFOG(28) instead, checked after the set-up (which
  // factors the shifted matrix), so a singular shifted saddle matrix (redundant constraint rows, σ
  // an eigenvalue) is still reported as Failed rather than solved with a wrong factor.
  MASTROM_PETSC_CALL(MatMumpsSetIcntl(factor, 24, 1));
  MASTROM_PETSC_CALL(EPSSetFromOptions(eps.get()));

  MASTROM_PETSC_CALL(EPSSetUp(eps.get()));
  MatSolverType solver_type = nullptr;
  MASTROM_PETSC_CALL(PCFactorGetMatSolverType(pc, &solver_type));
  if (solver_type != nullptr && std::string(solver_type) == MATSOLVERMUMPS) {
    MASTROM_PETSC_CALL(PCFactorGetMatrix(pc, &factor));
    PetscInt null_pivots = 0;
    MASTROM_PETSC_CALL(MatMumpsGetInfog(factor, 28, &null_pivots));
    if (null_pivots > 0) {
      raw.message = ::mastrom::detail::concat(
          "slepc: MUMPS found ", null_pivots,
          " null pivot(s) in the shifted saddle matrix [K − σM, Gᵀ; G, 0] (σ = ", sigma,
          "): it is singular — redundant constraint rows, or σ an eigenvalue");
      return raw;
    }
  }

  MASTROM_PETSC_CALL(EPSSolve(eps.get()));

  PetscInt nconv = 0;
  PetscInt iterations = 0;
  EPSConvergedReason reason = EPS_CONVERGED_ITERATING;
  MASTROM_PETSC_CALL(EPSGetConverged(eps.get(), &nconv));
  MASTROM_PETSC_CALL(EPSGetIterationNumber(eps.get(), &iterations));
  MASTROM_PETSC_CALL(EPSGetConvergedReason(eps.get(), &reason));
  // nconv may exceed nev; pairs come sorted nearest σ first.
  const PetscInt k = std::min<PetscInt>(nconv, options.count);

  raw.iterations = static_cast<int>(iterations);
  raw.values.resize(k);
  raw.vectors.resize(n, k);
  petsc::VecOwner x;
  MASTROM_PETSC_CALL(MatCreateVecs(a.get(), x.out(), nullptr));
  petsc::AllGather gather(x.get());
  for (PetscInt i = 0; i < k; ++i) {
    PetscScalar value = 0.0;
    MASTROM_PETSC_CALL(EPSGetEigenpair(eps.get(), i, &value, nullptr, x.get(), nullptr));
    raw.values(i) = value;
    raw.vectors.col(i) = gather(x.get()).head(n);  // drop the (scaled) multipliers
  }
  int size = 1;
  MPI_Comm_size(comm, &size);
  raw.status = k == options.count ? EigenStatus::Converged : EigenStatus::NotConverged;
  raw.message = ::mastrom::detail::concat(
      "slepc: ", k, " of ", options.count, " eigenpairs converged in ", iterations, " restarts (",
      EPSConvergedReasons[reason], ", ", size, size == 1 ? " rank)" : " ranks)");
  return raw;
}

}  // namespace mastrom::modes::detail
