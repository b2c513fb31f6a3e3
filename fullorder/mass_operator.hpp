// Products with the constant mass matrix, M x, for the time integrator's residuals (two
// to four per step). Every NCF and ANCF mass is M = M̄ ⊗ I₃ — one scalar mass density couples the x,
// y and z components of the coordinates alike — so M̄ (a ninth of the entries) is applied to whole
// xyz triples; any other mass is applied as it is.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace mastrom::fullorder {

/// M̄ when M = M̄ ⊗ I₃ with the coordinates in xyz triples (x, y, z of a vector consecutive), else an
/// empty (0 × 0) matrix.
Eigen::SparseMatrix<double> scalarMassOfTriples(const Eigen::SparseMatrix<double>& mass);

class MassOperator {
public:
  MassOperator() = default;
  explicit MassOperator(const Eigen::SparseMatrix<double>& mass);

  Eigen::Index size() const { return mass_.rows(); }
  /// True when M = M̄ ⊗ I₃ was recognised.
  bool perComponent() const { return scalar_.rows() > 0; }
  /// y = M x (y of size n; may not alias x).
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const;
  /// y −= M x (may not alias x).
  void subtract(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const;

private:
  template <bool kSubtract>
  void accumulate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const;

  Eigen::SparseMatrix<double> mass_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> scalar_;  ///< M̄ by rows, or empty
};

}  // namespace mastrom::fullorder
