// Sparse LDLᵀ factorisation of a saddle-point matrix (docs/theory.md §5.1a)
//     H = [ A  Gᵀ ]
//         [ G  0  ]
// with A (n × n) symmetric, positive definite on the null space of G, and G (m × n) of full row
// rank, for solves whose cost grows like the number of entries of the factor.
//
// The Schur complement route (fullorder/schur_complement.hpp) keeps W = A⁻¹Gᵀ dense (n × m) and
// S = G A⁻¹ Gᵀ dense (m × m): on a mast both n and m grow with the number of modules, so a solve
// costs O(n m) and a factorisation O(m n_L + m³) — quadratic and cubic in the modules. Here H is
// factorised as a whole: its unknowns are ordered by AMD on the pattern of A + GᵀG (the coupling
// the constraints add), each constraint placed right after the last of the unknowns it touches.
// Every leading block of P H Pᵀ in that order is then [A₁ G₁ᵀ; G₁ 0] with A₁ a principal block of A
// and G₁ of full row rank, so P H Pᵀ = L D Lᵀ exists without pivoting: D > 0 at the unknowns, D < 0
// at the constraints when A is positive definite. For a chain of modules the factor stays banded,
// so its size, a factorisation and a solve grow linearly with the modules. The factor is stored by
// supernodes (fullorder/supernodal_factor.hpp) as L|D|^½ with the signs of D.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

#include "fullorder/supernodal_factor.hpp"

namespace mastrom::fullorder {

class SaddleLdlt {
public:
  SaddleLdlt();
  ~SaddleLdlt();
  SaddleLdlt(const SaddleLdlt&) = delete;
  SaddleLdlt& operator=(const SaddleLdlt&) = delete;

  /// Order and analyse the pattern of H for `a` (its lower triangle) and `g`; compute() does this
  /// itself when the patterns change. Afterwards factorEntries() tells the cost of a solve.
  void analyze(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& g);
  /// Factorise H for `a` (n × n; only its lower triangle is read) and `g` (m × n); compressed
  /// matrices are read without a copy. False when a pivot has the wrong sign (A not positive
  /// definite where the ordering needs it) or a constraint's pivot is at round-off of the largest
  /// one (G without full row rank: redundant constraints); no factor is then available.
  bool compute(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& g);
  bool ready() const { return ready_; }
  /// n + m.
  Eigen::Index size() const;
  /// Entries of L below its diagonal in the analysed ordering (0 before analyze()).
  std::size_t factorEntries() const;
  const SupernodalFactor& factor() const { return packed_; }

  /// x = H⁻¹ b for b, x of size n + m (may not alias). No allocation after the first call.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

private:
  bool samePatterns(const Eigen::SparseMatrix<double>& a,
                    const Eigen::SparseMatrix<double>& g) const;

  struct Analysis;
  std::unique_ptr<Analysis> analysis_;
  bool ready_ = false;
  SupernodalFactor packed_;
};

/// How a saddle-point matrix is solved: through the Schur complement of its (1,1) block
/// (SchurComplement), through the LDLᵀ factor of the whole matrix (SaddleLdlt), or by whichever
/// makes a solve cheaper (saddleLdltIsCheaper, decided once per pattern).
enum class SaddleRoute { cheaper, schur_complement, whole_ldlt };

/// What one multiply–add of a sparse triangular solve (indirect rows, short supernodes) costs in
/// multiply–adds of a dense product: measured 2.3 on the Scheme 3 masts of 4–16 modules
/// (benchmarks/bench_fullorder_solvers.cpp, SchurSupernodal against SaddleLdltSolve). Taken as 4,
/// so that the default 4-module mast, where both routes are within 5 %, keeps the Schur route and
/// its numbers; from 8 modules on the LDLᵀ factor is clearly faster and is taken.
inline constexpr double kSparseOperationCost = 4.0;

/// Whether a solve with H costs less through SaddleLdlt (`ldlt_entries` = factorEntries(): two
/// sparse operations per entry and unknown) than through the Schur complement of A
/// (SchurComplement: A's solve, `block_solve_cost` in dense multiply–adds, then the dense W y, n·m,
/// and S's two triangles, m²).
bool saddleLdltIsCheaper(std::size_t ldlt_entries, double block_solve_cost, Eigen::Index n,
                         Eigen::Index m);

}  // namespace mastrom::fullorder
