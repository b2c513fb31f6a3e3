// Sign and cluster conventions of mode sets (see mode_basis.hpp).
#include "modes/mode_basis.hpp"

#include <algorithm>
#include <cmath>

namespace mastrom::modes {
namespace {

bool sameCluster(const Eigen::VectorXd& w2, Eigen::Index j, double tolerance, double scale) {
  return std::abs(w2[j] - w2[j - 1]) <= tolerance * std::max(std::abs(w2[j]), 1e-12 * scale);
}

}  // namespace

void normaliseColumnSigns(Eigen::Ref<Eigen::MatrixXd> columns) {
  for (Eigen::Index j = 0; j < columns.cols(); ++j) {
    const double largest = columns.col(j).cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < columns.rows(); ++i) {
      if (std::abs(columns(i, j)) >= (1.0 - 1e-6) * largest) {
        if (columns(i, j) < 0.0) columns.col(j) *= -1.0;
        break;
      }
    }
  }
}

std::vector<std::pair<int, int>> degenerateClusters(const Eigen::VectorXd& omega_squared,
                                                    double tolerance) {
  std::vector<std::pair<int, int>> clusters;
  const int n = static_cast<int>(omega_squared.size());
  if (n == 0) return clusters;
  const double scale = omega_squared.cwiseAbs().maxCoeff();
  for (int i = 0; i < n;) {
    int j = i + 1;
    while (j < n && sameCluster(omega_squared, j, tolerance, scale)) ++j;
    if (j - i >= 2) clusters.emplace_back(i, j);
    i = j;
  }
  return clusters;
}

int countWithWholeClusters(const Eigen::VectorXd& omega_squared, int wanted, double tolerance) {
  const int n = static_cast<int>(omega_squared.size());
  if (n == 0) return 0;
  const double scale = omega_squared.cwiseAbs().maxCoeff();
  int kept = std::min(wanted, n);
  while (kept >= 1 && kept < n && sameCluster(omega_squared, kept, tolerance, scale)) ++kept;
  return kept;
}

}  // namespace mastrom::modes
