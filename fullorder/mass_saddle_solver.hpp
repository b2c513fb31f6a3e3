// Solver for the constant-mass saddle-point matrix of the index-1 equations (docs/theory.md §5,
// [LW24] eq. 45)
//     A = [ M  Gᵀ ]        A [x; λ] = [b₁; b₂],
//         [ G  0  ]
// by its Schur complement (fullorder/schur_complement.hpp). M is constant and symmetric positive
// definite (NCF and ANCF masses), so it is factorised once; for each Jacobian G (m × n, full row
// rank) only W = M⁻¹Gᵀ and the Cholesky factor of S = G M⁻¹ Gᵀ are formed. When M = M̄ ⊗ I₃
// (coordinates in xyz triples, as for every NCF and ANCF mass) only M̄ is factorised and the M-solve
// runs on the triples. On the default Scheme 3 mast (n = 408, m = 78 after the elimination) a
// solve takes ~8 µs against ~45 µs with the sparse LU factors of A (profile: the index-1
// recovery solves were a third of a step).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

#include "fullorder/saddle_ldlt.hpp"

namespace mastrom::fullorder {

class MassSaddleSolver {
public:
  /// Factorise M (n × n). positiveDefinite() tells whether that worked; if not, the caller needs
  /// another method (a semi-definite M makes A's (1,1) block singular, which A may survive).
  /// `route`: Schur complement or the whole matrix's LDLᵀ factor (saddle_ldlt.hpp), decided on the
  /// first G for `cheaper`.
  explicit MassSaddleSolver(const Eigen::SparseMatrix<double>& mass,
                            SaddleRoute route = SaddleRoute::cheaper);
  ~MassSaddleSolver();
  MassSaddleSolver(const MassSaddleSolver&) = delete;
  MassSaddleSolver& operator=(const MassSaddleSolver&) = delete;

  bool positiveDefinite() const { return positive_definite_; }
  /// True when M = M̄ ⊗ I₃ was recognised and only M̄ is factorised.
  bool perComponentMass() const;
  /// True when the solves go through the LDLᵀ factor of the whole matrix (after the first G).
  bool solvesWhole() const;
  /// Form W and the factor of S for this G (m × n). NumericalError when S is not positive definite
  /// (redundant constraints: G without full row rank), naming t [s] for context.
  void setConstraintJacobian(const Eigen::SparseMatrix<double>& g, double t);
  /// x = A⁻¹ b for b, x of size n + m. No allocation after the first call.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

private:
  /// x ← M⁻¹ x (n values).
  void solveMassInPlace(double* x);
  void copyTripleFactor();

  struct Factors;
  std::unique_ptr<Factors> factors_;
  Eigen::Index n_ = 0;
  Eigen::SparseMatrix<double> mass_;  ///< M (compressed)
  SaddleRoute route_;
  bool positive_definite_ = false;
};

}  // namespace mastrom::fullorder
