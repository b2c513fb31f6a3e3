#include "fullorder/mass_operator.hpp"

#include <vector>

#include "common/error.hpp"

namespace mastrom::fullorder {

Eigen::SparseMatrix<double> scalarMassOfTriples(const Eigen::SparseMatrix<double>& mass) {
  const Eigen::Index n = mass.rows();
  if (n == 0 || n % 3 != 0 || mass.cols() != n) return {};
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(mass, j); it; ++it) {
      const Eigen::Index i = it.row();
      if (it.value() == 0.0) continue;
      if (i % 3 != j % 3) return {};  // couples different components
      // The same value at every component of the 3 × 3 block.
      for (int c = 1; c < 3; ++c)
        if (mass.coeff(i - i % 3 + (i % 3 + c) % 3, j - j % 3 + (j % 3 + c) % 3) != it.value())
          return {};
      if (i % 3 == 0) entries.emplace_back(i / 3, j / 3, it.value());
    }
  Eigen::SparseMatrix<double> scalar(n / 3, n / 3);
  scalar.setFromTriplets(entries.begin(), entries.end());
  scalar.makeCompressed();
  return scalar;
}

MassOperator::MassOperator(const Eigen::SparseMatrix<double>& mass)
    : mass_(mass), scalar_(scalarMassOfTriples(mass)) {
  MASTROM_REQUIRE(mass.rows() == mass.cols(), Error, "mass operator: M is ", mass.rows(), " x ",
                  mass.cols());
  mass_.makeCompressed();
}

template <bool kSubtract>
void MassOperator::accumulate(const Eigen::Ref<const Eigen::VectorXd>& x,
                              Eigen::Ref<Eigen::VectorXd> y) const {
  MASTROM_ASSERT(x.size() == mass_.cols() && y.size() == mass_.rows() && x.data() != y.data());
  if (!perComponent()) {
    if (kSubtract) {
      y.noalias() -= mass_ * x;
    } else {
      y.noalias() = mass_ * x;
    }
    return;
  }
  if (!kSubtract) y.setZero();
  // Column j of M̄ scales the triple j of x into the triples of its rows.
  const int* start = scalar_.outerIndexPtr();
  const int* row = scalar_.innerIndexPtr();
  const double* value = scalar_.valuePtr();
  const double* in = x.data();
  double* out = y.data();
  const double sign = kSubtract ? -1.0 : 1.0;
  for (Eigen::Index j = 0; j < scalar_.cols(); ++j) {
    const double x0 = sign * in[3 * j], x1 = sign * in[3 * j + 1], x2 = sign * in[3 * j + 2];
    for (int p = start[j]; p < start[j + 1]; ++p) {
      double* to = out + 3 * row[p];
      to[0] += value[p] * x0;
      to[1] += value[p] * x1;
      to[2] += value[p] * x2;
    }
  }
}

void MassOperator::apply(const Eigen::Ref<const Eigen::VectorXd>& x,
                         Eigen::Ref<Eigen::VectorXd> y) const {
  accumulate<false>(x, y);
}

void MassOperator::subtract(const Eigen::Ref<const Eigen::VectorXd>& x,
                            Eigen::Ref<Eigen::VectorXd> y) const {
  accumulate<true>(x, y);
}

}  // namespace mastrom::fullorder
