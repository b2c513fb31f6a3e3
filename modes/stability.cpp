#include "modes/stability.hpp"

#include <petscksp.h>

#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "modes/eigen_backends.hpp"
#include "modes/petsc_wrap.hpp"

namespace mastrom::modes {
namespace {

using KspOwner = petsc::Owner<KSP, KSPDestroy>;

/// MUMPS ICNTL(14): extra working space [%] for delayed pivots (as the SLEPc backend sets it).
constexpr PetscInt kMumpsWorkspacePercent = 100;
/// First trial shift below zero and the factor between trials when searching a shift below the
/// lowest eigenvalue: (2π · 1 Hz)², then ×100 up to kMaxShiftSteps times (to ~(2π·1e15 Hz)²).
constexpr double kFirstShift = -39.47841760435743;
constexpr double kShiftFactor = 100.0;
constexpr int kMaxShiftSteps = 15;
/// Above this many free directions the lowest pair is found with ARPACK instead of dense.
constexpr Eigen::Index kDenseLimit = 400;

}  // namespace

ShiftInertia constrainedInertia(const ConstrainedEigenproblem& problem, double sigma) {
  if (!SlepcSession::active())
    throw UsageError("constrainedInertia called without an active SlepcSession");
  const petsc::QuietErrors quiet;
  const double scale = detail::constraintScale(problem, sigma);
  const petsc::MatOwner a =
      petsc::toPetscMatrix(detail::saddleMatrix(problem, sigma, scale), PETSC_COMM_SELF);
  MASTROM_PETSC_CALL(MatSetOption(a.get(), MAT_SYMMETRIC, PETSC_TRUE));

  KspOwner ksp;
  MASTROM_PETSC_CALL(KSPCreate(PETSC_COMM_SELF, ksp.out()));
  MASTROM_PETSC_CALL(KSPSetOperators(ksp.get(), a.get(), a.get()));
  MASTROM_PETSC_CALL(KSPSetType(ksp.get(), KSPPREONLY));
  PC pc = nullptr;  // borrowed from ksp
  MASTROM_PETSC_CALL(KSPGetPC(ksp.get(), &pc));
  // Cholesky of a symmetric AIJ matrix with MUMPS = LDLᵀ with 1 × 1 and 2 × 2 pivots (SYM = 2),
  // which factors the indefinite saddle matrix and counts its negative pivots.
  MASTROM_PETSC_CALL(PCSetType(pc, PCCHOLESKY));
  MASTROM_PETSC_CALL(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  MASTROM_PETSC_CALL(PCFactorSetUpMatSolverType(pc));
  Mat factor = nullptr;  // borrowed from pc
  MASTROM_PETSC_CALL(PCFactorGetMatrix(pc, &factor));
  MASTROM_PETSC_CALL(MatMumpsSetIcntl(factor, 14, kMumpsWorkspacePercent));
  // ICNTL(13) = 1: the root node is factored by MUMPS itself, not ScaLAPACK, so INFOG(12) counts
  // every negative pivot; ICNTL(24) = 1: zero pivots are detected and counted in INFOG(28).
  MASTROM_PETSC_CALL(MatMumpsSetIcntl(factor, 13, 1));
  MASTROM_PETSC_CALL(MatMumpsSetIcntl(factor, 24, 1));
  MASTROM_PETSC_CALL(KSPSetUp(ksp.get()));
  PetscInt negative = 0, null_pivots = 0;
  MASTROM_PETSC_CALL(PCFactorGetMatrix(pc, &factor));
  MASTROM_PETSC_CALL(MatMumpsGetInfog(factor, 12, &negative));
  MASTROM_PETSC_CALL(MatMumpsGetInfog(factor, 28, &null_pivots));
  const auto m = static_cast<PetscInt>(problem.constraints());
  MASTROM_REQUIRE(negative >= m, NumericalError, "stability check: the saddle matrix has ",
                  negative, " negative pivots, fewer than its ", m,
                  " constraint rows: the constraint Jacobian is rank deficient");
  return {static_cast<int>(negative - m), static_cast<int>(null_pivots)};
}

double StabilityReport::lowestFrequencyHz() const {
  const double magnitude = std::sqrt(std::abs(lowest_omega2)) / (2.0 * M_PI);
  return lowest_omega2 < 0 ? -magnitude : magnitude;
}

std::string StabilityReport::describe() const {
  if (!checked) return "not checked";
  if (stable() && !branch.empty()) return "stable, " + branch;
  if (stable())
    return neutral > 0 ? ::mastrom::detail::concat("stable (", neutral, " neutral direction",
                                                   neutral == 1 ? "" : "s", ")")
                       : std::string("stable");
  char text[256];
  std::snprintf(text, sizeof text,
                "%d unstable direction%s: lowest eigenvalue omega^2 = %.6g rad^2/s^2 (f = %.6g Hz)"
                "%s%s%s",
                negative, negative == 1 ? "" : "s", lowest_omega2, lowestFrequencyHz(),
                lowest_label.empty() ? "" : ", shape '", lowest_label.c_str(),
                lowest_label.empty() ? "" : "'");
  return text;
}

StabilityReport checkStability(const ConstrainedEigenproblem& problem) {
  StabilityReport report;
  const ShiftInertia at_zero = constrainedInertia(problem, 0.0);
  report.checked = true;
  report.negative = at_zero.below;
  report.neutral = at_zero.at;
  if (report.stable()) return report;

  // A shift below every eigenvalue: then the pair nearest it is the lowest one.
  double sigma = kFirstShift;
  int step = 0;
  while (constrainedInertia(problem, sigma).below > 0) {
    MASTROM_REQUIRE(++step < kMaxShiftSteps, NumericalError, "stability check: no shift down to ",
                    sigma, " rad^2/s^2 lies below the lowest eigenvalue");
    sigma *= kShiftFactor;
  }
  EigenSolverOptions options;
  options.count = 1;
  options.target_rad2_s2 = sigma;
  options.backend = problem.dofs() - problem.constraints() <= kDenseLimit
                        ? EigenBackendKind::Dense
                        : EigenBackendKind::Arpack;
  const EigenResult lowest = solveConstrainedEigenproblem(problem, options);
  MASTROM_REQUIRE(lowest.converged >= 1, NumericalError,
                  "stability check: the lowest eigenpair below the shift ", sigma,
                  " did not converge: ", lowest.message);
  report.lowest_omega2 = lowest.eigenvalues_rad2_s2(0);
  report.lowest_shape = lowest.modes.col(0);
  return report;
}

}  // namespace mastrom::modes
