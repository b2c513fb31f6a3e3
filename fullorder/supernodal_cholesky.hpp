// Sparse Cholesky factor P A Pᵀ = L Lᵀ of a symmetric positive definite matrix, stored by
// supernodes for fast repeated solves (the time integrator solves with one factorisation
// of its iteration matrix for thousands of steps, so the cost of a solve is what counts).
//
// The numeric factor comes from Eigen's SimplicialLLT with an AMD ordering; it is then stored by
// supernodes (fullorder/supernodal_factor.hpp). On the default Scheme 3 iteration matrix's
// (1,1) block (408 unknowns, 20 517 entries of L in 42 supernodes) a whole saddle solve through
// SchurComplement takes 23.7 µs over this factor, 38.5 µs over SimplicialLLT::solve and 45.9 µs
// with the sparse LU of the saddle matrix (benchmarks/bench_fullorder_solvers.cpp;
// tests/fullorder/test_supernodal_cholesky.cpp checks the results).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

#include "fullorder/supernodal_factor.hpp"

namespace mastrom::fullorder {

class SupernodalCholesky {
public:
  SupernodalCholesky();
  ~SupernodalCholesky();
  SupernodalCholesky(const SupernodalCholesky&) = delete;
  SupernodalCholesky& operator=(const SupernodalCholesky&) = delete;

  /// Factorise the symmetric matrix whose lower triangle `a` holds (the upper one is not read).
  /// The ordering is analysed on the first call and kept while the pattern stays the same. Returns
  /// false when a is not numerically positive definite (no factor is then available).
  bool compute(const Eigen::SparseMatrix<double>& a);
  bool ready() const { return ready_; }
  Eigen::Index size() const { return n_; }
  /// Entries of L, its diagonal included (the operations of a solve: two per entry).
  std::size_t factorEntries() const { return factor_entries_; }
  int supernodeCount() const { return packed_.supernodeCount(); }
  /// Doubles stored in the panels (the diagonal blocks as full squares).
  std::size_t panelEntries() const { return packed_.panelEntries(); }

  /// x ← A⁻¹ x (n values). No allocation.
  void solveInPlace(double* x) const;

private:
  struct Factor;  // Eigen's SimplicialLLT: keeps the analysed ordering between calls
  std::unique_ptr<Factor> factor_;
  Eigen::Index n_ = 0;
  bool ready_ = false;
  std::size_t factor_entries_ = 0;
  SupernodalFactor packed_;
};

}  // namespace mastrom::fullorder
