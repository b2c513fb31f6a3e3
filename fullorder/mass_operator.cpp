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
  scalar_.makeCompressed();
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
  // By rows, y_i = Σ_j M̄(i, j) x_j on the triples: running sums and one store per triple (the
  // column-scatter form stores after every entry: 3.6 against 2.2 µs on Scheme 3).
  const int* start = scalar_.outerIndexPtr();
  const int* column = scalar_.innerIndexPtr();
  const double* value = scalar_.valuePtr();
  const double* in = x.data();
  double* out = y.data();
  for (Eigen::Index i = 0; i < scalar_.rows(); ++i) {
    // Two sums per component, so consecutive entries do not wait on each other's addition.
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, t0 = 0.0, t1 = 0.0, t2 = 0.0;
    int p = start[i];
    for (; p + 2 <= start[i + 1]; p += 2) {
      const double* a = in + 3 * column[p];
      const double* b = in + 3 * column[p + 1];
      s0 += value[p] * a[0];
      s1 += value[p] * a[1];
      s2 += value[p] * a[2];
      t0 += value[p + 1] * b[0];
      t1 += value[p + 1] * b[1];
      t2 += value[p + 1] * b[2];
    }
    if (p < start[i + 1]) {
      const double* a = in + 3 * column[p];
      s0 += value[p] * a[0];
      s1 += value[p] * a[1];
      s2 += value[p] * a[2];
    }
    double* to = out + 3 * i;
    if (kSubtract) {
      to[0] -= s0 + t0;
      to[1] -= s1 + t1;
      to[2] -= s2 + t2;
    } else {
      to[0] = s0 + t0;
      to[1] = s1 + t1;
      to[2] = s2 + t2;
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
