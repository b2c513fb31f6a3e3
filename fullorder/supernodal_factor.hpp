// A sparse triangular factor L of P H Pᵀ = L D̂ Lᵀ (D̂ = diag(±1)), stored by supernodes for fast
// repeated solves: SupernodalCholesky packs its Cholesky factor (D̂ = I), SaddleLdlt the scaled
// LDLᵀ factor of a saddle-point matrix (D̂ the signs of its pivots).
//
// The columns of L are grouped into fundamental supernodes — runs of consecutive columns whose rows
// below the diagonal block coincide — and every supernode is stored as one dense column-major panel
// (its lower triangular diagonal block over its off-diagonal rows, each column packed after the
// previous one, so no zeros above the diagonal are stored or streamed through). A solve then runs,
// per supernode, a small dense triangular solve and one dense panel product with a gather or
// scatter of its rows, instead of one indirect update per stored entry.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace mastrom::fullorder {

class SupernodalFactor {
public:
  /// Pack `l` (lower triangular, compressed, every column sorted by row with its diagonal first)
  /// with the permutation (P x)[permutation[i]] = x[i] and the positions of P H Pᵀ whose pivot is
  /// negative (D̂ = −1 there; empty for a Cholesky factor).
  void pack(const Eigen::SparseMatrix<double>& l, std::vector<int> permutation,
            std::vector<int> negative_pivots);
  Eigen::Index size() const { return n_; }
  int supernodeCount() const { return static_cast<int>(supernodes_.size()); }
  /// Doubles stored in the panels (the diagonal blocks as packed lower triangles).
  std::size_t panelEntries() const { return panels_.size(); }

  /// x ← H⁻¹ x (n values). No allocation.
  void solveInPlace(double* x) const;

  /// Storage of one supernode (for the solve kernels in the .cpp).
  struct Supernode {
    int first_column = 0;  ///< of the permuted matrix
    int columns = 0;
    int off_rows = 0;       ///< rows below the diagonal block
    /// Offset in panels_ of the packed panel: column c holds its columns − c rows of the diagonal
    /// block, then its off_rows rows (columns (columns + 1) / 2 + columns off_rows entries).
    std::size_t panel = 0;
    std::size_t rows = 0;   ///< offset of the off-diagonal row indices in rows_
  };

private:
  Eigen::Index n_ = 0;
  std::vector<int> permutation_;  ///< (P x)[permutation_[i]] = x[i]
  std::vector<int> negative_;     ///< permuted positions whose D̂ is −1
  std::vector<Supernode> supernodes_;
  std::vector<double> panels_;
  std::vector<int> rows_;
  mutable std::vector<double> work_, gathered_;  ///< n values; rows of the largest panel
};

}  // namespace mastrom::fullorder
