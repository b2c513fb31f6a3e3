// Functions of symmetric positive-definite (SPD) matrices for the manifold interpolation of
// docs/theory.md §4.4 (b): square root, inverse square root, logarithm and exponential through the
// eigendecomposition A = U diag(λ) Uᵀ (f(A) = U diag(f(λ)) Uᵀ), and the log/exp maps of the SPD
// manifold with its affine-invariant metric at a base point P:
//
//     Log_P(S) = P^½ log(P^-½ S P^-½) P^½        (tangent vector at P: a symmetric matrix)
//     Exp_P(T) = P^½ exp(P^-½ T P^-½) P^½        (back on the manifold: SPD for every symmetric T)
//
// (Pennec, Fillard & Ayache 2006; Amsallem & Farhat 2011 use it to interpolate reduced matrices.)
// Exp_P(Log_P(S)) = S, so an interpolant that reproduces its tangent vectors at the samples
// reproduces the samples, and any linear combination of tangent vectors — extrapolation included —
// maps back to an SPD matrix.
//
// Contract: inputs must be square and symmetric to 1e-10 of their largest entry (only the
// symmetric part ½(A + Aᵀ) is used); functions that need A to be SPD throw NumericalError naming
// `what` when it is not: smallest eigenvalue ≤ kSpdRelativeFloor · largest, or not finite.
// Everything is O(k³) dense work: meant for the small reduced matrices (k ≲ 100) of a ROM.
#pragma once

#include <string>

#include <Eigen/Core>

namespace mastrom::rom {

/// An eigenvalue at or below this fraction of the largest counts as "not positive": the matrix is
/// numerically singular and its log/inverse square root would be dominated by round-off.
inline constexpr double kSpdRelativeFloor = 1e-14;

/// A^½ (SPD). Throws NumericalError when A is not SPD.
Eigen::MatrixXd spdSqrt(const Eigen::Ref<const Eigen::MatrixXd>& a,
                        const std::string& what = "matrix");
/// A^-½ (SPD). Throws NumericalError when A is not SPD.
Eigen::MatrixXd spdInverseSqrt(const Eigen::Ref<const Eigen::MatrixXd>& a,
                               const std::string& what = "matrix");
/// log A (symmetric; A SPD). Throws NumericalError when A is not SPD.
Eigen::MatrixXd spdLog(const Eigen::Ref<const Eigen::MatrixXd>& a,
                       const std::string& what = "matrix");
/// exp T of a symmetric T (always SPD). Throws NumericalError when T is not finite or an
/// eigenvalue exceeds 700 (exp would overflow).
Eigen::MatrixXd symmetricExp(const Eigen::Ref<const Eigen::MatrixXd>& t,
                             const std::string& what = "matrix");

/// The base point of the affine-invariant log/exp maps, with P^½ and P^-½ computed once.
class SpdBasePoint {
public:
  /// Throws NumericalError when P is not SPD.
  explicit SpdBasePoint(const Eigen::Ref<const Eigen::MatrixXd>& p,
                        const std::string& what = "base point");

  Eigen::Index size() const { return sqrt_.rows(); }
  const Eigen::MatrixXd& sqrt() const { return sqrt_; }          ///< P^½

  /// Log_P(S) = P^½ log(P^-½ S P^-½) P^½. Throws NumericalError when S is not SPD.
  Eigen::MatrixXd log(const Eigen::Ref<const Eigen::MatrixXd>& s,
                      const std::string& what = "matrix") const;
  /// Exp_P(T) = P^½ exp(P^-½ T P^-½) P^½ for a symmetric T.
  Eigen::MatrixXd exp(const Eigen::Ref<const Eigen::MatrixXd>& t,
                      const std::string& what = "tangent vector") const;

  /// The whitened logarithm log(P^-½ S P^-½) (a tangent vector at the identity). Interpolating
  /// these and mapping back with expWhitened saves two congruences per evaluation.
  Eigen::MatrixXd logWhitened(const Eigen::Ref<const Eigen::MatrixXd>& s,
                              const std::string& what = "matrix") const;
  /// P^½ exp(X) P^½ for a symmetric X = whitened tangent vector.
  Eigen::MatrixXd expWhitened(const Eigen::Ref<const Eigen::MatrixXd>& x,
                              const std::string& what = "tangent vector") const;

private:
  Eigen::MatrixXd sqrt_, inv_sqrt_;
};

}  // namespace mastrom::rom
