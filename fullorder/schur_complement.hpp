// Solves of the saddle-point matrix
//     [ A  Gᵀ ] [x]   [b₁]
//     [ G  0  ] [y] = [b₂]
// through its Schur complement, given a fast solve with the (1,1) block A (symmetric positive
// definite; n × n) and G (m × n, full row rank, m ≪ n). Forming W = A⁻¹Gᵀ (dense n × m, m solves
// with A) and the Cholesky factor of S = G W (m × m) once, every solve is
//     z = A⁻¹ b₁,   y = S⁻¹(G z − b₂),   x = z − W y:
// one solve with A, two dense products and a small triangular pair. Used for the constant-mass
// matrix of the index-1 recovery (MassSaddleSolver) and for the iteration matrix of the time
// integrator (IterationSaddleSolver), whose A blocks have their own fast solves.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>

namespace mastrom::fullorder {

class SchurComplement {
public:
  /// y = A⁻¹ b in place (n values).
  using BlockSolve = std::function<void(double* x)>;

  /// Form W and the factor of S for this A-solve and G; the A-solve is kept for solve(). Returns
  /// false when S is not numerically positive definite (G without full row rank: redundant
  /// constraints), which the caller reports with its own context.
  bool setup(BlockSolve solve_a, Eigen::Index n, const Eigen::SparseMatrix<double>& g);
  bool ready() const { return ready_; }
  /// x = [A Gᵀ; G 0]⁻¹ b for b, x of size n + m (may not alias). No allocation after the first
  /// call.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);

private:
  BlockSolve solve_a_;
  Eigen::Index n_ = 0;
  bool ready_ = false;
  Eigen::SparseMatrix<double> g_;
  Eigen::MatrixXd w_;                  ///< A⁻¹Gᵀ (n × m)
  Eigen::LLT<Eigen::MatrixXd> schur_;  ///< of S = G A⁻¹ Gᵀ
  Eigen::VectorXd y_;                  ///< work space (m)
};

}  // namespace mastrom::fullorder
