#include "fullorder/schur_complement.hpp"

#include "common/cpu_features.hpp"
#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {
/// x −= W y for a column-major n × m matrix W: four columns per pass over x (W is the largest
/// operand of a solve: 408 × 78 on Scheme 3, read once per solve).
MASTROM_ALWAYS_INLINE void subtractProductBody(const double* w, Eigen::Index n, Eigen::Index m,
                                               const double* y, double* x) {
  Eigen::Index k = 0;
  for (; k + 4 <= m; k += 4) {
    const double* w0 = w + k * n;
    const double* w1 = w0 + n;
    const double* w2 = w1 + n;
    const double* w3 = w2 + n;
    const double y0 = y[k], y1 = y[k + 1], y2 = y[k + 2], y3 = y[k + 3];
    for (Eigen::Index i = 0; i < n; ++i)
      x[i] -= (w0[i] * y0 + w1[i] * y1) + (w2[i] * y2 + w3[i] * y3);
  }
  for (; k < m; ++k) {
    const double* wk = w + k * n;
    const double yk = y[k];
    for (Eigen::Index i = 0; i < n; ++i) x[i] -= wk[i] * yk;
  }
}

void subtractProductBaseline(const double* w, Eigen::Index n, Eigen::Index m, const double* y,
                             double* x) {
  subtractProductBody(w, n, m, y, x);
}

#if MASTROM_HAVE_AVX2_KERNELS
__attribute__((target("avx2,fma"))) void subtractProductAvx2(const double* w, Eigen::Index n,
                                                             Eigen::Index m, const double* y,
                                                             double* x) {
  subtractProductBody(w, n, m, y, x);
}
#endif

void subtractProduct(const Eigen::MatrixXd& w, const Eigen::VectorXd& y, double* x) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return subtractProductAvx2(w.data(), w.rows(), w.cols(), y.data(), x);
#endif
  subtractProductBaseline(w.data(), w.rows(), w.cols(), y.data(), x);
}
}  // namespace

bool SchurComplement::setup(BlockSolve solve_a, Eigen::Index n,
                            const Eigen::SparseMatrix<double>& g) {
  MASTROM_REQUIRE(g.cols() == n, Error, "Schur complement: G has ", g.cols(), " columns for ", n,
                  " unknowns");
  ready_ = false;
  solve_a_ = std::move(solve_a);
  n_ = n;
  g_ = g;
  w_ = Eigen::MatrixXd(g.transpose());
  for (Eigen::Index k = 0; k < g.rows(); ++k) solve_a_(w_.col(k).data());
  const Eigen::MatrixXd s = g * w_;
  schur_.compute(s);
  // Rank deficiency shows as a pivot at round-off of the largest one (or a failed factorisation).
  bool regular = schur_.info() == Eigen::Success && s.allFinite();
  if (regular && s.rows() > 0) {
    const Eigen::VectorXd pivots = schur_.matrixLLT().diagonal().array().square();
    regular = pivots.minCoeff() > 1e-13 * pivots.maxCoeff();
  }
  y_.resize(g.rows());
  ready_ = regular;
  return regular;
}

void SchurComplement::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  MASTROM_ASSERT(ready_);
  const Eigen::Index n = n_, m = g_.rows();
  MASTROM_ASSERT(b.size() == n + m && &b != &x);
  x.resize(n + m);
  x.head(n) = b.head(n);
  // A right-hand side in the constraint rows only (a correction of Φ alone) needs no solve with A:
  // z = A⁻¹·0 = 0.
  if (x.head(n).isZero(0.0)) {
    y_ = -b.tail(m);
  } else {
    solve_a_(x.data());
    y_.noalias() = g_ * x.head(n);
    y_ -= b.tail(m);
  }
  schur_.solveInPlace(y_);
  subtractProduct(w_, y_, x.data());
  x.tail(m) = y_;
}

}  // namespace mastrom::fullorder
