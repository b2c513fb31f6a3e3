#include "rom/offline/mode_tracking.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <limits>

#include "common/error.hpp"

namespace mastrom::rom {

std::vector<int> maximumWeightAssignment(const Eigen::MatrixXd& weight) {
  const int n = static_cast<int>(weight.rows()), m = static_cast<int>(weight.cols());
  MASTROM_REQUIRE(n <= m, InputError, "assignment: ", n, " rows cannot be matched to ", m,
                  " columns");
  MASTROM_REQUIRE(weight.allFinite(), InputError, "assignment: non-finite weight");
  if (n == 0) return {};
  // Minimum-cost form with cost = −weight; u, v are the row and column potentials, p[j] the row
  // matched to column j (1-based, column 0 is the virtual start), way[] the augmenting path.
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  const auto cost = [&weight](int i, int j) { return -weight(i - 1, j - 1); };
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(m + 1, inf);
    std::vector<char> used(m + 1, 0);
    do {
      used[j0] = 1;
      const int i0 = p[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double cur = cost(i0, j) - u[i0] - v[j];
        if (cur < minv[j]) {
          minv[j] = cur;
          way[j] = j0;
        }
        if (minv[j] < delta) {
          delta = minv[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> result(n, -1);
  for (int j = 1; j <= m; ++j)
    if (p[j] != 0) result[p[j] - 1] = j - 1;
  return result;
}

ModeTracking trackModes(const Eigen::MatrixXd& phi_sample, const Eigen::MatrixXd& phi_reference,
                        const Eigen::SparseMatrix<double>& mass) {
  const Eigen::Index n = phi_reference.rows(), k_ref = phi_reference.cols(),
                     k_s = phi_sample.cols();
  MASTROM_REQUIRE(
      phi_sample.rows() == n && mass.rows() == n && mass.cols() == n && k_s >= k_ref && k_ref >= 1,
      InputError, "mode tracking: sizes disagree (", phi_sample.rows(), " x ", k_s,
      " sample modes, ", n, " x ", k_ref, " reference modes, mass ", mass.rows(), " x ",
      mass.cols(), ")");
  const Eigen::MatrixXd m_ref = mass * phi_reference;            // M Φ_ref
  const Eigen::MatrixXd cross = phi_sample.transpose() * m_ref;  // Φ_sᵀ M Φ_ref
  const Eigen::VectorXd norm_ref = (phi_reference.transpose() * m_ref).diagonal();
  const Eigen::MatrixXd m_s = mass * phi_sample;
  const Eigen::VectorXd norm_s = (phi_sample.transpose() * m_s).diagonal();
  MASTROM_REQUIRE((norm_ref.array() > 0).all() && (norm_s.array() > 0).all(), InputError,
                  "mode tracking: a mode has zero mass norm");

  Eigen::MatrixXd mac(k_ref, k_s);  // rows: reference modes
  for (Eigen::Index j = 0; j < k_ref; ++j)
    for (Eigen::Index i = 0; i < k_s; ++i)
      mac(j, i) = cross(i, j) * cross(i, j) / (norm_s[i] * norm_ref[j]);

  ModeTracking t;
  t.tracking = maximumWeightAssignment(mac);
  t.sign.resize(k_ref);
  t.mac.resize(k_ref);
  for (Eigen::Index j = 0; j < k_ref; ++j) {
    const int i = t.tracking[j];
    t.sign[j] = cross(i, j) < 0.0 ? -1 : 1;
    t.mac[j] = mac(j, i);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(cross, Eigen::ComputeThinU | Eigen::ComputeThinV);
  t.alignment = svd.matrixU() * svd.matrixV().transpose();
  return t;
}

}  // namespace mastrom::rom
