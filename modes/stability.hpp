// Is a linearisation point a stable equilibrium? Counting the negative eigenvalues of the
// constrained tangent without computing them.
//
// The equilibrium (q*, λ*) of a conservative constrained system is stable when the second
// variation of the potential is positive on the constraint tangent space, i.e. when ZᵀKZ is
// positive definite for a basis Z of null(G) (K the tangent with the multiplier term,
// modes/linearize.hpp). Its negative eigenvalues are the unstable directions: the constrained
// pencil (K, M) has exactly as many negative ω² (Sylvester's law of inertia, ZᵀMZ being positive
// definite). They are counted from one symmetric indefinite factorisation of the saddle matrix:
// for G of full row rank m,
//     In([K − σM, Gᵀ; G, 0]) = In(Zᵀ(K − σM)Z) + (m, m, 0)
// (Gould 1985, "On practical conditions for the existence and uniqueness of solutions to the
// general equality quadratic programming problem", Math. Programming 32, eq. (2.3); the same
// spectrum-slicing count is the Sturm sequence check of Bathe, "Finite Element Procedures",
// §11.4.3). So the number of constrained eigenvalues ω² < σ is the number of negative pivots of the
// LDLᵀ factorisation (MUMPS, 1 × 1 and 2 × 2 pivots, INFOG(12)) minus m. At σ = 0 it is the count
// of unstable directions; the factorisation is the one a shift-and-invert eigen-solve at σ = 0
// makes anyway.
//
// When the count is not zero, the lowest eigenpair is found for the message: σ is lowered (×100
// per step, each step one more factorisation) until no eigenvalue lies below it, then the pair
// nearest that σ — the lowest one — is solved for by shift-and-invert.
#pragma once

#include <Eigen/Core>
#include <string>

#include "modes/eigen_solver.hpp"

namespace mastrom::modes {

/// The inertia of the constrained pencil relative to a shift σ.
struct ShiftInertia {
  int below = 0;  ///< constrained eigenvalues ω² < σ (negative pivots minus m)
  int at = 0;     ///< null pivots: ω² = σ to the factorisation's precision
};

/// Count the constrained eigenvalues below `sigma` [rad²/s²] with one LDLᵀ factorisation
/// (PETSc/MUMPS on PETSC_COMM_SELF; needs an active SlepcSession). NumericalError when the
/// factorisation fails or the count is impossible (fewer negative pivots than constraints: G is
/// rank deficient).
ShiftInertia constrainedInertia(const ConstrainedEigenproblem& problem, double sigma);

/// Outcome of the stability check of a linearisation point.
struct StabilityReport {
  bool checked = false;          ///< false: not examined (the report says so)
  int negative = 0;              ///< unstable directions (constrained eigenvalues ω² < 0)
  int neutral = 0;               ///< zero pivots at σ = 0 (ω² = 0 to round-off: a mechanism)
  double lowest_omega2 = 0.0;    ///< the lowest eigenvalue ω² [rad²/s²] when negative > 0
  Eigen::VectorXd lowest_shape;  ///< its mode shape (n), M-normalised
  std::string lowest_label;      ///< filled by the caller that can label shapes
  /// How a stable equilibrium was reached when the first one found was unstable ("" = directly).
  std::string branch;

  bool stable() const { return negative == 0; }
  /// −sqrt(−ω²)/2π of the lowest eigenvalue [Hz] (the sign convention of EigenResult).
  double lowestFrequencyHz() const;
  /// One line for people, e.g. "1 unstable direction: lowest eigenvalue ω² = −1.672e+07 rad²/s²
  /// (f = −650.78 Hz), shape 'shell n=3'".
  std::string describe() const;
};

/// Check `problem` as the header says. The lowest pair is solved with the dense backend for small
/// models (n − m ≤ 400) and ARPACK otherwise.
StabilityReport checkStability(const ConstrainedEigenproblem& problem);

}  // namespace mastrom::modes
