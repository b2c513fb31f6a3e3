// The constrained ordering, the numeric LDLᵀ factor and its supernodal solves (see the header).
#include "fullorder/saddle_ldlt.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {
using Sparse = Eigen::SparseMatrix<double>;

bool samePattern(const Sparse& a, const Sparse& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a.nonZeros() == b.nonZeros() &&
         a.isCompressed() && b.isCompressed() &&
         std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

Sparse onesOf(const Sparse& m) {
  Sparse ones = m;
  ones.coeffs().setOnes();
  return ones;
}
}  // namespace

namespace {
/// Eigen's LDLᵀ, whose factor's size is known from the symbolic analysis alone: matrixL() asserts
/// a numeric factorisation, though analyzePattern already sized the factor (its column pointers).
class PatternSizedLdlt
    : public Eigen::SimplicialLDLT<Sparse, Eigen::Upper, Eigen::NaturalOrdering<int>> {
public:
  Eigen::Index factorNonZeros() const { return m_matrix.nonZeros(); }
};
}  // namespace

struct SaddleLdlt::Analysis {
  /// P H Pᵀ is handed over as its upper triangle in the order of the analysis: no ordering of
  /// Eigen's own.
  PatternSizedLdlt ldlt;
  Sparse a_pattern, g_pattern;  ///< of the analysed matrices (values unused)
  Sparse permuted;              ///< upper triangle of P H Pᵀ, fixed pattern
  /// Where each entry of a (−1: above its diagonal, not read) and of g goes in permuted.
  std::vector<int> a_target, g_target;
  std::vector<int> position;        ///< (P x)[position[i]] = x[i]
  std::vector<char> constraint_at;  ///< by permuted position: a constraint's row of H
  Eigen::Index n = 0, m = 0;
  Sparse scaled;  ///< L|D|^½ with its diagonal, for the packing
};

SaddleLdlt::SaddleLdlt() = default;
SaddleLdlt::~SaddleLdlt() = default;

Eigen::Index SaddleLdlt::size() const { return analysis_ ? analysis_->n + analysis_->m : 0; }

std::size_t SaddleLdlt::factorEntries() const {
  return analysis_ ? static_cast<std::size_t>(analysis_->ldlt.factorNonZeros()) : 0;
}

bool SaddleLdlt::samePatterns(const Sparse& a, const Sparse& g) const {
  return analysis_ && samePattern(a, analysis_->a_pattern) && samePattern(g, analysis_->g_pattern);
}

void SaddleLdlt::analyze(const Sparse& a, const Sparse& g) {
  if (!a.isCompressed() || !g.isCompressed()) {
    Sparse a_compressed = a, g_compressed = g;
    a_compressed.makeCompressed();
    g_compressed.makeCompressed();
    return analyze(a_compressed, g_compressed);
  }
  MASTROM_REQUIRE(a.rows() == a.cols() && g.cols() == a.rows(), Error, "saddle LDLT: A is ",
                  a.rows(), " x ", a.cols(), " and G ", g.rows(), " x ", g.cols(),
                  " (G needs A's columns)");
  ready_ = false;
  auto s = std::make_unique<Analysis>();
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(g.rows());
  s->n = n;
  s->m = m;
  s->a_pattern = a;
  s->g_pattern = g;

  // The unknowns' elimination order: AMD on A's pattern with every constraint's unknowns made a
  // clique (GᵀG), the fill that eliminating the constraint after them causes.
  const Sparse a_ones = onesOf(a), g_ones = onesOf(g);
  const Sparse graph =
      Sparse(a_ones + Sparse(a_ones.transpose())) + Sparse(Sparse(g_ones.transpose()) * g_ones);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;  // order[k] = unknown
  Eigen::AMDOrdering<int>()(graph, order);
  std::vector<int> rank(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) rank[static_cast<std::size_t>(order.indices()[k])] = k;

  // Each constraint right after the last of its unknowns (an empty row at the very end: its zero
  // pivot then refuses the matrix).
  std::vector<int> last(static_cast<std::size_t>(m), -1);
  for (int j = 0; j < n; ++j)
    for (Sparse::InnerIterator it(g, j); it; ++it) {
      int& l = last[static_cast<std::size_t>(it.row())];
      l = std::max(l, rank[static_cast<std::size_t>(j)]);
    }
  std::vector<std::vector<int>> after(static_cast<std::size_t>(n) + 1);
  for (int r = 0; r < m; ++r) {
    const int l = last[static_cast<std::size_t>(r)];
    after[static_cast<std::size_t>(l < 0 ? n : l)].push_back(r);
  }
  s->position.assign(static_cast<std::size_t>(n + m), -1);
  s->constraint_at.assign(static_cast<std::size_t>(n + m), 0);
  int next = 0;
  for (int k = 0; k <= n; ++k) {
    if (k < n) s->position[static_cast<std::size_t>(order.indices()[k])] = next++;
    for (int r : after[static_cast<std::size_t>(k)]) {
      s->constraint_at[static_cast<std::size_t>(next)] = 1;
      s->position[static_cast<std::size_t>(n + r)] = next++;
    }
  }

  // The permuted upper triangle, with each source entry's number as its value to find it again.
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(a.nonZeros() + g.nonZeros()));
  const auto add = [&](int row, int col, double id) {
    const int i = s->position[static_cast<std::size_t>(row)],
              j = s->position[static_cast<std::size_t>(col)];
    t.emplace_back(std::min(i, j), std::max(i, j), id);
  };
  for (int j = 0; j < n; ++j)
    for (int p = a.outerIndexPtr()[j]; p < a.outerIndexPtr()[j + 1]; ++p)
      if (a.innerIndexPtr()[p] >= j) add(a.innerIndexPtr()[p], j, static_cast<double>(p));
  for (int j = 0; j < n; ++j)
    for (int p = g.outerIndexPtr()[j]; p < g.outerIndexPtr()[j + 1]; ++p)
      add(n + g.innerIndexPtr()[p], j, static_cast<double>(a.nonZeros() + p));
  s->permuted.resize(n + m, n + m);
  s->permuted.setFromTriplets(t.begin(), t.end());  // no duplicates: distinct entries of H
  s->permuted.makeCompressed();
  s->a_target.assign(static_cast<std::size_t>(a.nonZeros()), -1);
  s->g_target.assign(static_cast<std::size_t>(g.nonZeros()), -1);
  for (Eigen::Index q = 0; q < s->permuted.nonZeros(); ++q) {
    const auto id = static_cast<Eigen::Index>(s->permuted.valuePtr()[q]);
    if (id < a.nonZeros())
      s->a_target[static_cast<std::size_t>(id)] = static_cast<int>(q);
    else
      s->g_target[static_cast<std::size_t>(id - a.nonZeros())] = static_cast<int>(q);
  }
  s->ldlt.analyzePattern(s->permuted);
  analysis_ = std::move(s);
}

bool SaddleLdlt::compute(const Sparse& a, const Sparse& g) {
  if (!a.isCompressed() || !g.isCompressed()) {  // the value maps index compressed storage
    Sparse a_compressed = a, g_compressed = g;
    a_compressed.makeCompressed();
    g_compressed.makeCompressed();
    return compute(a_compressed, g_compressed);
  }
  if (!samePatterns(a, g)) analyze(a, g);
  ready_ = false;
  Analysis& s = *analysis_;
  double* v = s.permuted.valuePtr();
  for (std::size_t p = 0; p < s.a_target.size(); ++p)
    if (s.a_target[p] >= 0) v[s.a_target[p]] = a.valuePtr()[p];
  for (std::size_t p = 0; p < s.g_target.size(); ++p) v[s.g_target[p]] = g.valuePtr()[p];
  s.ldlt.factorize(s.permuted);
  if (s.ldlt.info() != Eigen::Success) return false;  // a zero pivot

  // The signs the ordering guarantees for a positive definite A and G of full row rank; a
  // constraint's pivot at round-off of the largest one shows rank deficiency (as the Schur
  // complement's pivots do in SchurComplement::setup).
  const Eigen::VectorXd& d = s.ldlt.vectorD();
  const Eigen::Index size = s.n + s.m;
  double largest_constraint = 0.0, smallest_constraint = std::numeric_limits<double>::infinity();
  std::vector<int> negative;
  negative.reserve(static_cast<std::size_t>(s.m));
  for (Eigen::Index k = 0; k < size; ++k) {
    const bool constraint = s.constraint_at[static_cast<std::size_t>(k)] != 0;
    if (!std::isfinite(d[k]) || (constraint ? d[k] >= 0.0 : d[k] <= 0.0)) return false;
    if (constraint) {
      largest_constraint = std::max(largest_constraint, -d[k]);
      smallest_constraint = std::min(smallest_constraint, -d[k]);
      negative.push_back(static_cast<int>(k));
    }
  }
  if (s.m > 0 && !(smallest_constraint > 1e-13 * largest_constraint)) return false;

  // L|D|^½ with its diagonal first in every column (Eigen's LDLᵀ factor stores L's strictly lower
  // part, rows sorted), the layout SupernodalFactor packs.
  const Sparse& l = s.ldlt.matrixL().nestedExpression();
  Sparse& scaled = s.scaled;
  scaled.resize(size, size);
  scaled.resizeNonZeros(l.nonZeros() + size);
  int* start = scaled.outerIndexPtr();
  int* row = scaled.innerIndexPtr();
  double* value = scaled.valuePtr();
  start[0] = 0;
  for (Eigen::Index j = 0; j < size; ++j) {
    const double root = std::sqrt(std::abs(d[j]));
    int q = start[j];
    row[q] = static_cast<int>(j);
    value[q++] = root;
    for (int p = l.outerIndexPtr()[j]; p < l.outerIndexPtr()[j + 1]; ++p) {
      row[q] = l.innerIndexPtr()[p];
      value[q++] = l.valuePtr()[p] * root;
    }
    start[j + 1] = q;
  }
  if (!scaled.coeffs().allFinite()) return false;
  packed_.pack(scaled, s.position, std::move(negative));
  ready_ = true;
  return true;
}

void SaddleLdlt::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  MASTROM_ASSERT(ready_ && b.size() == size() && &b != &x);
  x = b;
  packed_.solveInPlace(x.data());
}

bool saddleLdltIsCheaper(std::size_t ldlt_entries, double block_solve_cost, Eigen::Index n,
                         Eigen::Index m) {
  const double ldlt =
      kSparseOperationCost * 2.0 * (static_cast<double>(ldlt_entries) + static_cast<double>(n + m));
  const double schur = block_solve_cost + static_cast<double>(n) * static_cast<double>(m) +
                       static_cast<double>(m) * static_cast<double>(m);
  return ldlt < schur;
}

}  // namespace mastrom::fullorder
