// Symmetric positive definite test matrices shaped like the mast's stiffness blocks: nodes of three
// coordinates (xyz), each coupled densely to its next `reach` − 1 neighbours along a chain, made
// definite by diagonal dominance. Shared by the sparse Cholesky and Schur-complement tests.
#pragma once

#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <random>

namespace mastrom::fullorder::testing {

inline Eigen::SparseMatrix<double> tripleChainSpd(int nodes, int reach, double diagonal,
                                                  std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3 * nodes, 3 * nodes);
  for (int b = 0; b < nodes; ++b)
    for (int c = b; c < std::min(nodes, b + reach); ++c)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double v = u(gen);
          a(3 * b + i, 3 * c + j) += v;
          a(3 * c + j, 3 * b + i) += v;
        }
  a.diagonal().array() += diagonal;
  return a.sparseView();
}

/// The dense saddle-point matrix [A Gᵀ; G 0].
inline Eigen::MatrixXd denseSaddle(const Eigen::MatrixXd& a, const Eigen::MatrixXd& g) {
  const Eigen::Index n = a.rows(), m = g.rows();
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(n + m, n + m);
  h.topLeftCorner(n, n) = a;
  h.bottomLeftCorner(m, n) = g;
  h.topRightCorner(n, m) = g.transpose();
  return h;
}

/// Normwise backward error |H x − b|∞ / (|H|∞ |x|∞ + |b|∞).
inline double backwardError(const Eigen::MatrixXd& h, const Eigen::VectorXd& x,
                            const Eigen::VectorXd& b) {
  const double h_norm = h.cwiseAbs().rowwise().sum().maxCoeff();
  return (h * x - b).cwiseAbs().maxCoeff() /
         (h_norm * x.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff());
}

}  // namespace mastrom::fullorder::testing
