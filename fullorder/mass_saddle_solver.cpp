#include "fullorder/mass_saddle_solver.hpp"

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>

#include "common/error.hpp"

namespace mastrom::fullorder {

struct MassSaddleSolver::Factors {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> mass;  ///< of M (AMD ordering)
  Eigen::SparseMatrix<double> g;                            ///< G of the current W and S
  Eigen::MatrixXd w;                                        ///< M⁻¹Gᵀ (n × m)
  Eigen::LLT<Eigen::MatrixXd> schur;                        ///< of S = G M⁻¹ Gᵀ
  Eigen::VectorXd y, lambda;                                ///< work space
  bool ready = false;
};

MassSaddleSolver::MassSaddleSolver(const Eigen::SparseMatrix<double>& mass)
    : factors_(std::make_unique<Factors>()) {
  factors_->mass.compute(mass);
  // LDLᵀ succeeds on indefinite matrices too: require every pivot > 0 (M SPD).
  positive_definite_ = factors_->mass.info() == Eigen::Success && mass.rows() > 0 &&
                       factors_->mass.vectorD().minCoeff() > 0.0;
}

MassSaddleSolver::~MassSaddleSolver() = default;

void MassSaddleSolver::setConstraintJacobian(const Eigen::SparseMatrix<double>& g, double t) {
  MASTROM_REQUIRE(positive_definite_, Error,
                  "mass saddle solver: M is not positive definite, use a factorisation of A");
  Factors& f = *factors_;
  MASTROM_REQUIRE(g.cols() == f.mass.rows(), Error, "mass saddle solver: G has ", g.cols(),
                  " columns for ", f.mass.rows(), " coordinates");
  f.g = g;
  f.w = f.mass.solve(Eigen::MatrixXd(g.transpose()));
  const Eigen::MatrixXd s = g * f.w;
  f.schur.compute(s);
  // Rank deficiency shows as a pivot at round-off of the largest one (or a failed factorisation).
  bool regular = f.schur.info() == Eigen::Success;
  if (regular && s.rows() > 0) {
    const Eigen::VectorXd pivots = f.schur.matrixLLT().diagonal().array().square();
    regular = pivots.minCoeff() > 1e-13 * pivots.maxCoeff();
  }
  MASTROM_REQUIRE(
      regular, NumericalError, "generalized-alpha: [M G'; G 0] is singular at t = ", t,
      " s (G M^-1 G' is not positive definite): redundant or inconsistent constraints?");
  f.y.resize(g.cols());
  f.lambda.resize(g.rows());
  f.ready = true;
}

void MassSaddleSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  Factors& f = *factors_;
  MASTROM_ASSERT(f.ready);
  const Eigen::Index n = f.g.cols(), m = f.g.rows();
  MASTROM_ASSERT(b.size() == n + m);
  f.y = f.mass.solve(b.head(n));
  f.lambda.noalias() = f.g * f.y;
  f.lambda -= b.tail(m);
  f.schur.solveInPlace(f.lambda);
  x.resize(n + m);
  x.head(n) = f.y;
  x.head(n).noalias() -= f.w * f.lambda;
  x.tail(m) = f.lambda;
}

}  // namespace mastrom::fullorder
