// The factorisations GeneralizedAlpha keeps and reuses: the iteration matrix (sparse LU, or the
// Schur complement over a supernodal Cholesky factor of its (1,1) block) and the index-1 matrix
// [M Φ_qᵀ; Φ_q 0] (docs/theory.md §5.1–5.2).
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "common/error.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/generalized_alpha_internal.hpp"
#include "fullorder/two_threads.hpp"

namespace mastrom::fullorder {

using generalized_alpha_detail::maxAbs;
using generalized_alpha_detail::recordInputs;

void GeneralizedAlpha::swapIterationFactors() {
  std::swap(solver_, spare_solver_);
  std::swap(iteration_inputs_, spare_inputs_);
  std::swap(factor_valid_, spare_valid_);
  std::swap(residual_per_position_, spare_residual_per_position_);
  row_residual_per_position_.swap(spare_row_residual_per_position_);
}

bool GeneralizedAlpha::iterationSolveBySchur() const { return solver_->block_ready; }

void GeneralizedAlpha::factorize(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                 const Eigen::VectorXd& lambda, double t,
                                 const IterationCoefficients& c, bool general_lu) {
  system_.iterationMatrix(q, qdot, lambda, t, c, iter_matrix_);
  // ∂(momentum residual)/∂q = H₁₁ / c_k [N/m] sets how far rounding the positions moves the
  // residual. Independent roundings of up to ε|q_j| add up like a random sum: per row
  // ε‖q‖∞ (Σ_j (∂r_i/∂q_j)²)^½, the largest row counts (the aligned worst case, the row 1-norm,
  // is 2× larger on Scheme 3). tests/fullorder/test_newton_floor.cpp: this bounds the residual
  // change of one-ulp roundings of all positions and is within 5× of it.
  {
    const int n = system_.dofCount();
    Eigen::VectorXd row_squares = Eigen::VectorXd::Zero(n);  // once per factorisation
    for (int j = 0; j < n; ++j)
      for (SparseMatrix::InnerIterator it(iter_matrix_, j); it; ++it)
        if (it.row() < n) row_squares[it.row()] += it.value() * it.value();
    residual_per_position_ =
        (n > 0 && c.stiffness > 0.0) ? std::sqrt(row_squares.maxCoeff()) / c.stiffness : 0.0;
    row_residual_per_position_ = c.stiffness > 0.0
                                     ? Eigen::VectorXd(row_squares.cwiseSqrt() / c.stiffness)
                                     : Eigen::VectorXd::Zero(n);
  }
  solver_->block_ready =
      !general_lu && options_.schur_iteration_solver && factorizeIterationBySchur();
  if (!solver_->block_ready) {
    if (!solver_->analysed) {
      solver_->lu.analyzePattern(iter_matrix_);
      solver_->analysed = true;
    }
    solver_->lu.factorize(iter_matrix_);
    MASTROM_REQUIRE(solver_->lu.info() == Eigen::Success, NumericalError,
                    "generalized-alpha: iteration matrix is singular at t = ", t, " s (",
                    solver_->lu.lastErrorMessage(), ")");
  }
  solver_->angle_rad = system_.rotationAngle(t);
  ++factorizations_;
  recordInputs(iteration_inputs_, q, qdot, lambda, t, c, general_lu);
}

bool GeneralizedAlpha::factorizeIterationBySchur() {
  // H = [A Gᵀ; G 0] with A = β′M-scaled inertia + damping + stiffness. A is symmetric up to the
  // damping force's dependence on q (and positive definite for the step sizes that resolve the
  // dynamics), so its symmetric part has a Cholesky factor, and the Schur complement turns that
  // into a solve with H that costs ~half of the sparse LU's (25 against 47 µs on
  // Scheme 3). Leaving out the antisymmetric part is a modified Newton like the reuse of a factor:
  // the iterates converge to the same solution, at a rate set by its size (measured 7e-6 of A on
  // Scheme 3, with elastic velocities of 1 cm/s). Only taken where that part is small; advance()
  // falls back to the LU when a fresh factor of this kind still contracts slowly.
  constexpr double kMaxAsymmetry = 1e-4;
  const int n = system_.dofCount(), m = system_.constraintCount();
  const SparseMatrix a = iter_matrix_.topLeftCorner(n, n);
  const SparseMatrix a_transposed = a.transpose();
  const double a_norm = a.norm();
  if (!(a_norm > 0.0) || SparseMatrix(a - a_transposed).norm() > kMaxAsymmetry * a_norm)
    return false;
  const SparseMatrix g = iter_matrix_.bottomLeftCorner(m, n);
  if (SparseMatrix(SparseMatrix(g.transpose()) - SparseMatrix(iter_matrix_.topRightCorner(n, m)))
              .norm() != 0.0 ||
      SparseMatrix(iter_matrix_.bottomRightCorner(m, m)).norm() != 0.0)
    return false;
  const SparseMatrix a_symmetric = 0.5 * (a + a_transposed);
  Solver& s = *solver_;
  if (s.saddle) return s.saddle->compute(a_symmetric, g);
  if (!s.block) s.block = std::make_unique<SupernodalCholesky>();
  if (!s.block->compute(a_symmetric)) return false;
  if (!s.route_chosen) {
    // Once per pattern (the iteration matrix's is fixed): where W = A⁻¹Gᵀ and S make a solve dearer
    // than the LDLᵀ factor of the whole matrix (a long mast), take that instead (saddle_ldlt.hpp).
    s.route_chosen = true;
    const SaddleRoute route = options_.saddle_route;
    auto saddle = std::make_unique<SaddleLdlt>();
    if (route != SaddleRoute::schur_complement) saddle->analyze(a_symmetric, g);
    if (route == SaddleRoute::whole_ldlt ||
        (route == SaddleRoute::cheaper &&
         saddleLdltIsCheaper(
             saddle->factorEntries(),
             kSparseOperationCost * 2.0 * static_cast<double>(s.block->factorEntries()), n, m))) {
      s.block.reset();
      s.saddle = std::move(saddle);
      return s.saddle->compute(a_symmetric, g);
    }
  }
  SupernodalCholesky* block = s.block.get();
  return s.block_schur.setup([block](double* x) { block->solveInPlace(x); }, n, g);
}

void GeneralizedAlpha::solve(Solver& solver, double t, const Eigen::VectorXd& rhs,
                             Eigen::VectorXd& sol, Eigen::VectorXd& rotated) {
  const auto apply_inverse = [&solver](const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    if (solver.schur) {
      solver.schur->solve(b, x);
    } else if (solver.block_ready && solver.saddle) {
      solver.saddle->solve(b, x);
    } else if (solver.block_ready) {
      solver.block_schur.solve(b, x);
    } else {
      x = solver.lu.solve(b);
    }
  };
  const RotationSymmetry* symmetry =
      options_.reuse_across_rotation ? system_.rotationSymmetry() : nullptr;
  if (symmetry == nullptr) {
    apply_inverse(rhs, sol);
    return;
  }
  // H(now) = P_δ H(then) P_δᵀ up to the change of the elastic state (DaeSystem::rotationSymmetry),
  // so H(now)⁻¹ b ≈ P_δ H(then)⁻¹ P_δᵀ b: a stale factorisation stays nearly exact while the mast
  // turns (measured on Scheme 3 after 1.5°: refinement contraction 1e-6 instead of 2.5e-2).
  const double delta = system_.rotationAngle(t) - solver.angle_rad;
  rotated = rhs;
  symmetry->rotate(-delta, rotated);
  apply_inverse(rotated, sol);
  symmetry->rotate(delta, sol);
}

void GeneralizedAlpha::factorizeMassSaddle(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                           const Eigen::VectorXd& lambda, double t,
                                           const SparseMatrix* jacobian) {
  // M is constant: factorise it once, then only the Schur complement follows Φ_q (the LU of the
  // whole saddle matrix remains for a semi-definite M).
  if (!mass_solver_->analysed && !mass_solver_->schur) {
    auto schur = std::make_unique<MassSaddleSolver>(system_.massMatrix(), options_.saddle_route);
    if (schur->positiveDefinite()) mass_solver_->schur = std::move(schur);
  }
  const IterationCoefficients saddle{1.0, 0.0, 0.0, 1.0};
  if (mass_solver_->schur) {
    if (jacobian != nullptr) {  // Φ_q(q, t) already at hand (the index-1 recovery's)
      mass_solver_->schur->setConstraintJacobian(*jacobian, t);
    } else {
      system_.constraintJacobian(q, t, mass_jacobian_);  // not jac_: it may hold another state's
      mass_solver_->schur->setConstraintJacobian(mass_jacobian_, t);
    }
  } else {
    system_.iterationMatrix(q, qdot, lambda, t, saddle, iter_matrix_);
    if (!mass_solver_->analysed) {
      mass_solver_->lu.analyzePattern(iter_matrix_);
      mass_solver_->analysed = true;
    }
    mass_solver_->lu.factorize(iter_matrix_);
    MASTROM_REQUIRE(mass_solver_->lu.info() == Eigen::Success, NumericalError,
                    "generalized-alpha: [M G'; G 0] is singular at t = ", t, " s (",
                    mass_solver_->lu.lastErrorMessage(),
                    "): redundant or inconsistent constraints?");
  }
  mass_solver_->angle_rad = system_.rotationAngle(t);
  ++mass_factorizations_;
  recordInputs(mass_inputs_, q, qdot, lambda, t, saddle, false);
}

}  // namespace mastrom::fullorder
