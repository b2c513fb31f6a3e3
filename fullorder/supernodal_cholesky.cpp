#include "fullorder/supernodal_cholesky.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>

#include "common/error.hpp"

namespace mastrom::fullorder {

struct SupernodalCholesky::Factor {
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> llt;
  Eigen::SparseMatrix<double> pattern;  ///< of the analysed matrix (values unused)
};

SupernodalCholesky::SupernodalCholesky() : factor_(std::make_unique<Factor>()) {}
SupernodalCholesky::~SupernodalCholesky() = default;

bool SupernodalCholesky::compute(const Eigen::SparseMatrix<double>& a) {
  MASTROM_REQUIRE(a.rows() == a.cols(), Error, "supernodal Cholesky: the matrix is ", a.rows(),
                  " x ", a.cols(), ", not square");
  ready_ = false;
  Factor& f = *factor_;
  const bool same_pattern =
      f.pattern.rows() == a.rows() && f.pattern.nonZeros() == a.nonZeros() && a.isCompressed() &&
      std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1,
                 f.pattern.outerIndexPtr()) &&
      std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), f.pattern.innerIndexPtr());
  if (!same_pattern) {
    f.pattern = a;
    f.pattern.makeCompressed();
    f.llt.analyzePattern(f.pattern);
  }
  f.llt.factorize(a);
  // SimplicialLLT reports a non-positive pivot as NumericalIssue.
  if (f.llt.info() != Eigen::Success) return false;
  n_ = a.rows();
  const Eigen::SparseMatrix<double> l = f.llt.matrixL();
  if (!l.coeffs().allFinite()) return false;
  factor_entries_ = static_cast<std::size_t>(l.nonZeros());
  packed_.pack(l,
               std::vector<int>(f.llt.permutationP().indices().data(),
                                f.llt.permutationP().indices().data() + n_),
               {});
  ready_ = true;
  return true;
}

void SupernodalCholesky::solveInPlace(double* x) const {
  MASTROM_ASSERT(ready_);
  packed_.solveInPlace(x);
}

}  // namespace mastrom::fullorder
