#include "rom/interpolation/spd_math.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "common/error.hpp"

namespace mastrom::rom {
namespace {

/// ½(A + Aᵀ) after checking A is square, finite and symmetric to 1e-10 of its largest entry.
Eigen::MatrixXd symmetricPart(const Eigen::Ref<const Eigen::MatrixXd>& a, const std::string& what) {
  MASTROM_REQUIRE(a.rows() == a.cols() && a.rows() >= 1, InputError, what, ": ", a.rows(), " × ",
                  a.cols(), " is not a non-empty square matrix");
  MASTROM_REQUIRE(a.allFinite(), NumericalError, what, ": non-finite entries");
  const double scale = a.cwiseAbs().maxCoeff();
  const double asym = (a - a.transpose()).cwiseAbs().maxCoeff();
  MASTROM_REQUIRE(asym <= 1e-10 * scale, NumericalError, what,
                  ": not symmetric (max|A − Aᵀ| = ", asym, ", max|A| = ", scale, ")");
  return 0.5 * (a + a.transpose());
}

/// Eigendecomposition of a symmetric matrix (ascending eigenvalues).
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> decompose(const Eigen::MatrixXd& sym,
                                                         const std::string& what) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(sym);
  MASTROM_REQUIRE(es.info() == Eigen::Success, NumericalError, what,
                  ": symmetric eigensolver did not converge");
  return es;
}

/// The same for a matrix that must be SPD.
Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> decomposeSpd(
    const Eigen::Ref<const Eigen::MatrixXd>& a, const std::string& what) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es = decompose(symmetricPart(a, what), what);
  const double lo = es.eigenvalues().minCoeff(), hi = es.eigenvalues().maxCoeff();
  MASTROM_REQUIRE(hi > 0.0 && lo > kSpdRelativeFloor * hi, NumericalError, what,
                  ": not symmetric positive definite (eigenvalues from ", lo, " to ", hi, ")");
  return es;
}

/// U diag(f(λ)) Uᵀ.
template <typename F>
Eigen::MatrixXd applyFunction(const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& es, F f) {
  const Eigen::MatrixXd& u = es.eigenvectors();
  const Eigen::VectorXd fl = es.eigenvalues().unaryExpr(f);
  Eigen::MatrixXd out;
  out.noalias() = u * fl.asDiagonal() * u.transpose();
  return 0.5 * (out + out.transpose());  // exactly symmetric
}

/// B A B for symmetric B (a congruence), symmetrised.
Eigen::MatrixXd congruence(const Eigen::MatrixXd& b, const Eigen::MatrixXd& a) {
  Eigen::MatrixXd out;
  out.noalias() = b * a * b;
  return 0.5 * (out + out.transpose());
}

}  // namespace

Eigen::MatrixXd spdSqrt(const Eigen::Ref<const Eigen::MatrixXd>& a, const std::string& what) {
  return applyFunction(decomposeSpd(a, what), [](double l) { return std::sqrt(l); });
}

Eigen::MatrixXd spdInverseSqrt(const Eigen::Ref<const Eigen::MatrixXd>& a,
                               const std::string& what) {
  return applyFunction(decomposeSpd(a, what), [](double l) { return 1.0 / std::sqrt(l); });
}

Eigen::MatrixXd spdLog(const Eigen::Ref<const Eigen::MatrixXd>& a, const std::string& what) {
  return applyFunction(decomposeSpd(a, what), [](double l) { return std::log(l); });
}

Eigen::MatrixXd symmetricExp(const Eigen::Ref<const Eigen::MatrixXd>& t, const std::string& what) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es = decompose(symmetricPart(t, what), what);
  MASTROM_REQUIRE(es.eigenvalues().maxCoeff() <= 700.0, NumericalError, what,
                  ": exp overflows (largest eigenvalue ", es.eigenvalues().maxCoeff(), ")");
  return applyFunction(es, [](double l) { return std::exp(l); });
}

SpdBasePoint::SpdBasePoint(const Eigen::Ref<const Eigen::MatrixXd>& p, const std::string& what) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es = decomposeSpd(p, what);
  sqrt_ = applyFunction(es, [](double l) { return std::sqrt(l); });
  inv_sqrt_ = applyFunction(es, [](double l) { return 1.0 / std::sqrt(l); });
}

Eigen::MatrixXd SpdBasePoint::logWhitened(const Eigen::Ref<const Eigen::MatrixXd>& s,
                                          const std::string& what) const {
  MASTROM_REQUIRE(s.rows() == size() && s.cols() == size(), InputError, what, ": ", s.rows(),
                  " × ", s.cols(), ", the base point is ", size(), " × ", size());
  // Whitening first: P^-½ S P^-½ is SPD iff S is, and its eigenvalues are the generalized ones of
  // (S, P) — ratios near 1 for S near P, so the logarithm is well scaled whatever the units of S.
  const Eigen::MatrixXd w = congruence(inv_sqrt_, symmetricPart(s, what));
  return spdLog(w, what);
}

Eigen::MatrixXd SpdBasePoint::expWhitened(const Eigen::Ref<const Eigen::MatrixXd>& x,
                                          const std::string& what) const {
  MASTROM_REQUIRE(x.rows() == size() && x.cols() == size(), InputError, what, ": ", x.rows(),
                  " × ", x.cols(), ", the base point is ", size(), " × ", size());
  return congruence(sqrt_, symmetricExp(x, what));
}

Eigen::MatrixXd SpdBasePoint::log(const Eigen::Ref<const Eigen::MatrixXd>& s,
                                  const std::string& what) const {
  return congruence(sqrt_, logWhitened(s, what));
}

Eigen::MatrixXd SpdBasePoint::exp(const Eigen::Ref<const Eigen::MatrixXd>& t,
                                  const std::string& what) const {
  MASTROM_REQUIRE(t.rows() == size() && t.cols() == size(), InputError, what, ": ", t.rows(),
                  " × ", t.cols(), ", the base point is ", size(), " × ", size());
  return expWhitened(congruence(inv_sqrt_, symmetricPart(t, what)), what);
}

}  // namespace mastrom::rom
