// Packing and solves of a supernodal triangular factor (see the header).
#include "fullorder/supernodal_factor.hpp"

#include <algorithm>

#include "common/cpu_features.hpp"
#include "common/error.hpp"

namespace mastrom::fullorder {

void SupernodalFactor::pack(const Eigen::SparseMatrix<double>& l, std::vector<int> permutation,
                            std::vector<int> negative_pivots) {
  MASTROM_REQUIRE(l.rows() == l.cols() && l.isCompressed() &&
                      static_cast<Eigen::Index>(permutation.size()) == l.rows(),
                  Error, "supernodal factor: a ", l.rows(), " x ", l.cols(), " factor with ",
                  permutation.size(), " permuted indices");
  n_ = l.rows();
  permutation_ = std::move(permutation);
  negative_ = std::move(negative_pivots);
  const int n = static_cast<int>(n_);
  const int* start = l.outerIndexPtr();
  const int* row = l.innerIndexPtr();
  const double* value = l.valuePtr();
  supernodes_.clear();
  panels_.clear();
  rows_.clear();
  // Packed, the panels hold exactly L's entries: one allocation, no growth copies.
  panels_.reserve(static_cast<std::size_t>(l.nonZeros()));
  std::size_t widest = 0;
  for (int j = 0; j < n;) {
    // Column c + 1 continues the supernode when column c's rows below c are exactly c + 1 followed
    // by column c + 1's rows below c + 1 (a fundamental supernode).
    int width = 1;
    for (int c = j; c + 1 < n; ++c, ++width) {
      const int below = start[c + 1] - start[c] - 1, next_below = start[c + 2] - start[c + 1] - 1;
      if (below != next_below + 1 || row[start[c] + 1] != c + 1 ||
          !std::equal(row + start[c] + 2, row + start[c + 1], row + start[c + 1] + 1))
        break;
    }
    Supernode s;
    s.first_column = j;
    s.columns = width;
    s.off_rows = start[j + 1] - start[j] - width;
    s.panel = panels_.size();
    s.rows = rows_.size();
    // Column j + c holds rows j + c … j + width − 1 of the diagonal block, then the shared rows,
    // packed one after the other: no square of zeros above the diagonal block, whose cache lines a
    // solve would otherwise stream past (a solve's cost at 64 modules is its factor's traffic:
    // docs/theory.md §5.2a).
    const std::size_t entries =
        static_cast<std::size_t>(width) * static_cast<std::size_t>(width + 1) / 2 +
        static_cast<std::size_t>(width) * static_cast<std::size_t>(s.off_rows);
    panels_.resize(panels_.size() + entries, 0.0);
    double* col = panels_.data() + s.panel;
    for (int c = 0; c < width; ++c) {
      const int first = start[j + c];
      const int in_block = width - c;
      for (int k = 0; k < in_block; ++k) col[k] = value[first + k];
      for (int k = 0; k < s.off_rows; ++k) col[in_block + k] = value[first + in_block + k];
      col += in_block + s.off_rows;
    }
    rows_.insert(rows_.end(), row + start[j] + width, row + start[j + 1]);
    widest = std::max(widest, static_cast<std::size_t>(s.off_rows));
    supernodes_.push_back(s);
    j += width;
  }
  work_.assign(static_cast<std::size_t>(n), 0.0);
  gathered_.assign(std::max<std::size_t>(widest, 1), 0.0);
}

namespace {
/// What a solve reads and writes, as plain pointers for the kernels below.
struct SolveData {
  int n;
  const int* permutation;
  const int* negative;  ///< permuted positions whose pivot sign is −1
  int negatives;
  const SupernodalFactor::Supernode* begin;
  const SupernodalFactor::Supernode* end;
  const double* panels;
  const int* rows;
  double* w;  ///< n values of work space
  double* t;  ///< off-diagonal rows of the largest supernode
};

MASTROM_ALWAYS_INLINE void supernodalSolve(const SolveData& d, double* x) {
  const int n = d.n;
  double* w = d.w;
  double* t = d.t;
  for (int i = 0; i < n; ++i) w[d.permutation[i]] = x[i];
  // L z = P x, supernode by supernode: the diagonal block, then push its columns' updates down.
  for (const SupernodalFactor::Supernode* s = d.begin; s != d.end; ++s) {
    const int k = s->columns, r = s->off_rows;
    const double* panel = d.panels + s->panel;
    double* xs = w + s->first_column;
    // Packed columns (pack()): column c starts with its diagonal entry, rows c … k − 1 of the
    // block, then its r off-diagonal rows.
    const double* col = panel;
    for (int c = 0; c < k; ++c) {
      const double v = xs[c] / col[0];
      xs[c] = v;
      for (int i = c + 1; i < k; ++i) xs[i] -= col[i - c] * v;
      col += k - c + r;
    }
    if (r == 0) continue;
    for (int i = 0; i < r; ++i) t[i] = 0.0;
    col = panel;
    for (int c = 0; c < k; ++c) {
      const double* off = col + (k - c);
      const double v = xs[c];
      for (int i = 0; i < r; ++i) t[i] += off[i] * v;
      col += k - c + r;
    }
    const int* rows = d.rows + s->rows;
    for (int i = 0; i < r; ++i) w[rows[i]] -= t[i];
  }
  // D̂ z: the pivot signs of an LDLᵀ factor (none for a Cholesky factor).
  for (int i = 0; i < d.negatives; ++i) w[d.negative[i]] = -w[d.negative[i]];
  // Lᵀ u = z, supernodes in reverse: gather the rows below, then the transposed diagonal block.
  for (const SupernodalFactor::Supernode* s = d.end; s != d.begin;) {
    --s;
    const int k = s->columns, r = s->off_rows;
    const double* panel = d.panels + s->panel;
    double* xs = w + s->first_column;
    // Column c of the packed panel starts c (k + r) − c (c − 1) / 2 entries in.
    const auto column = [panel, k, r](int c) {
      return panel + static_cast<std::ptrdiff_t>(c) * (k + r) -
             static_cast<std::ptrdiff_t>(c) * (c - 1) / 2;
    };
    if (r > 0) {
      const int* rows = d.rows + s->rows;
      for (int i = 0; i < r; ++i) t[i] = w[rows[i]];
      const double* diagonal = panel;
      for (int c = 0; c < k; ++c) {
        const double* col = diagonal + (k - c);
        diagonal += k - c + r;
        // Four partial sums: a single one makes the loop wait on each addition.
        double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
        int i = 0;
        for (; i + 4 <= r; i += 4) {
          a0 += col[i] * t[i];
          a1 += col[i + 1] * t[i + 1];
          a2 += col[i + 2] * t[i + 2];
          a3 += col[i + 3] * t[i + 3];
        }
        for (; i < r; ++i) a0 += col[i] * t[i];
        xs[c] -= (a0 + a1) + (a2 + a3);
      }
    }
    for (int c = k - 1; c >= 0; --c) {
      const double* col = column(c);
      double v = xs[c];
      for (int i = c + 1; i < k; ++i) v -= col[i - c] * xs[i];
      xs[c] = v / col[0];
    }
  }
  for (int i = 0; i < n; ++i) x[i] = w[d.permutation[i]];
}

void solveBaseline(const SolveData& d, double* x) { supernodalSolve(d, x); }

#if MASTROM_HAVE_AVX2_KERNELS
// The same body for AVX2 + FMA: the panel products then run four rows per instruction.
__attribute__((target("avx2,fma"))) void solveAvx2(const SolveData& d, double* x) {
  supernodalSolve(d, x);
}
#endif
}  // namespace

void SupernodalFactor::solveInPlace(double* x) const {
  const SolveData d{static_cast<int>(n_), permutation_.data(),
                    negative_.data(),     static_cast<int>(negative_.size()),
                    supernodes_.data(),   supernodes_.data() + supernodes_.size(),
                    panels_.data(),       rows_.data(),
                    work_.data(),         gathered_.data()};
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return solveAvx2(d, x);
#endif
  solveBaseline(d, x);
}

}  // namespace mastrom::fullorder
