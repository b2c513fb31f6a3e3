#include "fullorder/mass_saddle_solver.hpp"

#include <Eigen/SparseCholesky>
#include <vector>

#include "common/error.hpp"
#include "fullorder/mass_operator.hpp"
#include "fullorder/saddle_ldlt.hpp"
#include "fullorder/schur_complement.hpp"

namespace mastrom::fullorder {

struct MassSaddleSolver::Factors {
  /// Of M, or of M̄ when M = M̄ ⊗ I₃: then a solve is one sparse solve with three right-hand sides
  /// and a ninth of the factor (~2 µs instead of ~12 µs on Scheme 3).
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> mass;
  bool triples = false;
  /// M̄'s factor P M̄ Pᵀ = L D Lᵀ copied into plain arrays, for a solve that runs on the
  /// interleaved triples directly (Eigen's solve with a dense three-column right-hand side
  /// costs ~12 µs here, mostly overhead, against ~1 µs for these loops).
  std::vector<int> l_start, l_row;   ///< strictly lower part of L, by column
  std::vector<double> l_value;
  std::vector<int> lr_start, lr_column;  ///< the same entries by row
  std::vector<double> lr_value;
  std::vector<double> d_inverse;
  std::vector<int> permutation;      ///< (P v)[permutation[i]] = v[i]
  std::vector<double> work;          ///< n values
  Eigen::VectorXd general;             ///< work space of the solve without triples (n)
  SchurComplement schur;               ///< W = M⁻¹Gᵀ and the factor of S = G M⁻¹ Gᵀ
  /// Where W and S make a solve dearer than the LDLᵀ factor of the whole matrix (a long mast;
  /// chosen on the first G, whose pattern stays): that factor instead of `schur`.
  std::unique_ptr<SaddleLdlt> whole;
  bool route_chosen = false;
};

MassSaddleSolver::MassSaddleSolver(const Eigen::SparseMatrix<double>& mass, SaddleRoute route)
    : factors_(std::make_unique<Factors>()), n_(mass.rows()), mass_(mass), route_(route) {
  mass_.makeCompressed();
  const Eigen::SparseMatrix<double> scalar = scalarMassOfTriples(mass);
  factors_->triples = scalar.rows() > 0;
  factors_->mass.compute(factors_->triples ? scalar : mass);
  // LDLᵀ succeeds on indefinite matrices too: require every pivot > 0 (M SPD).
  positive_definite_ = factors_->mass.info() == Eigen::Success && mass.rows() > 0 &&
                       factors_->mass.vectorD().minCoeff() > 0.0;
  if (positive_definite_ && factors_->triples) copyTripleFactor();
}

void MassSaddleSolver::copyTripleFactor() {
  Factors& f = *factors_;
  const Eigen::SparseMatrix<double> l = f.mass.matrixL();  // unit diagonal: skipped below
  const Eigen::Index points = l.cols();
  f.l_start.assign(1, 0);
  f.l_row.clear();
  f.l_value.clear();
  for (Eigen::Index j = 0; j < points; ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(l, j); it; ++it)
      if (it.row() > j) {
        f.l_row.push_back(static_cast<int>(it.row()));
        f.l_value.push_back(it.value());
      }
    f.l_start.push_back(static_cast<int>(f.l_row.size()));
  }
  const Eigen::SparseMatrix<double, Eigen::RowMajor> l_rows = l;
  f.lr_start.assign(1, 0);
  f.lr_column.clear();
  f.lr_value.clear();
  for (Eigen::Index i = 0; i < points; ++i) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(l_rows, i); it; ++it)
      if (it.col() < i) {
        f.lr_column.push_back(static_cast<int>(it.col()));
        f.lr_value.push_back(it.value());
      }
    f.lr_start.push_back(static_cast<int>(f.lr_column.size()));
  }
  f.d_inverse.resize(static_cast<std::size_t>(points));
  for (Eigen::Index i = 0; i < points; ++i)
    f.d_inverse[static_cast<std::size_t>(i)] = 1.0 / f.mass.vectorD()[i];
  f.permutation.assign(f.mass.permutationP().indices().data(),
                       f.mass.permutationP().indices().data() + points);
  f.work.resize(static_cast<std::size_t>(n_));
}

MassSaddleSolver::~MassSaddleSolver() = default;

bool MassSaddleSolver::perComponentMass() const { return factors_->triples; }

bool MassSaddleSolver::solvesWhole() const { return factors_->whole != nullptr; }

void MassSaddleSolver::solveMassInPlace(double* x) {
  Factors& f = *factors_;
  if (!f.triples) {
    Eigen::Map<Eigen::VectorXd> v(x, n_);
    f.general = f.mass.solve(v);
    v = f.general;
    return;
  }
  // y = Pᵀ L⁻ᵀ D⁻¹ L⁻¹ P b, every scalar operation applied to a whole xyz triple.
  const int points = static_cast<int>(n_ / 3);
  double* w = f.work.data();
  const double* in = x;
  for (int i = 0; i < points; ++i) {
    double* to = w + 3 * f.permutation[static_cast<std::size_t>(i)];
    to[0] = in[3 * i];
    to[1] = in[3 * i + 1];
    to[2] = in[3 * i + 2];
  }
  // L z = P b by rows: z_i = b_i − Σ_{j<i} L(i, j) z_j, one store per triple (the column form
  // stores after every entry).
  const int* row_start = f.lr_start.data();
  const int* column = f.lr_column.data();
  const double* row_value = f.lr_value.data();
  for (int i = 0; i < points; ++i) {
    double c0 = w[3 * i], c1 = w[3 * i + 1], c2 = w[3 * i + 2];
    for (int p = row_start[i]; p < row_start[i + 1]; ++p) {
      const double* t = w + 3 * column[p];
      c0 -= row_value[p] * t[0];
      c1 -= row_value[p] * t[1];
      c2 -= row_value[p] * t[2];
    }
    w[3 * i] = c0;
    w[3 * i + 1] = c1;
    w[3 * i + 2] = c2;
  }
  const int* start = f.l_start.data();
  const int* row = f.l_row.data();
  const double* value = f.l_value.data();
  for (int j = 0; j < points; ++j) {
    const double d = f.d_inverse[static_cast<std::size_t>(j)];
    w[3 * j] *= d;
    w[3 * j + 1] *= d;
    w[3 * j + 2] *= d;
  }
  for (int j = points - 1; j >= 0; --j) {  // Lᵀ u = D⁻¹ z (rows of Lᵀ = columns of L)
    double c0 = w[3 * j], c1 = w[3 * j + 1], c2 = w[3 * j + 2];
    for (int p = start[j]; p < start[j + 1]; ++p) {
      const double* t = w + 3 * row[p];
      c0 -= value[p] * t[0];
      c1 -= value[p] * t[1];
      c2 -= value[p] * t[2];
    }
    w[3 * j] = c0;
    w[3 * j + 1] = c1;
    w[3 * j + 2] = c2;
  }
  double* out = x;
  for (int i = 0; i < points; ++i) {
    const double* from = w + 3 * f.permutation[static_cast<std::size_t>(i)];
    out[3 * i] = from[0];
    out[3 * i + 1] = from[1];
    out[3 * i + 2] = from[2];
  }
}

void MassSaddleSolver::setConstraintJacobian(const Eigen::SparseMatrix<double>& g, double t) {
  MASTROM_REQUIRE(positive_definite_, Error,
                  "mass saddle solver: M is not positive definite, use a factorisation of A");
  MASTROM_REQUIRE(g.cols() == n_, Error, "mass saddle solver: G has ", g.cols(), " columns for ",
                  n_, " coordinates");
  Factors& f = *factors_;
  if (!f.route_chosen) {
    // Once (Φ_q's pattern is fixed): where W = M⁻¹Gᵀ and S make a solve dearer than the LDLᵀ factor
    // of the whole matrix (a long mast), take that instead.
    f.route_chosen = true;
    auto whole = std::make_unique<SaddleLdlt>();
    if (route_ != SaddleRoute::schur_complement) whole->analyze(mass_, g);
    // A solve with M: two operations per entry of its factor; with triples on each of x, y and z
    // in one pass, as fast per operation as a dense product (solveMassInPlace), else through
    // Eigen's sparse solve.
    const double entries = static_cast<double>(f.mass.matrixL().nestedExpression().nonZeros()) +
                           static_cast<double>(f.mass.rows());
    const double block_cost = f.triples ? 6.0 * entries : kSparseOperationCost * 2.0 * entries;
    if (route_ == SaddleRoute::whole_ldlt ||
        (route_ == SaddleRoute::cheaper &&
         saddleLdltIsCheaper(whole->factorEntries(), block_cost, n_, g.rows())))
      f.whole = std::move(whole);
  }
  const bool regular = f.whole ? f.whole->compute(mass_, g)
                               : f.schur.setup([this](double* x) { solveMassInPlace(x); }, n_, g);
  MASTROM_REQUIRE(
      regular, NumericalError, "generalized-alpha: [M G'; G 0] is singular at t = ", t,
      " s (G M^-1 G' is not positive definite): redundant or inconsistent constraints?");
}

void MassSaddleSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (factors_->whole) return factors_->whole->solve(b, x);
  factors_->schur.solve(b, x);
}

}  // namespace mastrom::fullorder
