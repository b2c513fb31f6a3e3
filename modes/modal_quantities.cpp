#include "modes/modal_quantities.hpp"

#include "common/error.hpp"

namespace mastrom::modes {
namespace {

/// MAC from the cross products C = ΦᵀMΨ and the self norms a_i = φ_iᵀMφ_i, b_j = ψ_jᵀMψ_j.
Eigen::MatrixXd macFromProducts(const Eigen::MatrixXd& cross, const Eigen::VectorXd& a,
                                const Eigen::VectorXd& b) {
  MASTROM_REQUIRE((a.array() > 0.0).all() && (b.array() > 0.0).all(), InputError,
                  "MAC: a mode has zero (or non-positive) norm");
  Eigen::MatrixXd mac = cross.array().square();
  mac.array().colwise() /= a.array();
  mac.array().rowwise() /= b.transpose().array();
  return mac;
}

void requireRows(Eigen::Index phi_rows, Eigen::Index psi_rows, Eigen::Index mass_size) {
  MASTROM_REQUIRE(phi_rows == psi_rows && phi_rows == mass_size, InputError, "MAC: mode sets have ",
                  phi_rows, " and ", psi_rows, " rows, the mass matrix ", mass_size);
}

}  // namespace

Eigen::MatrixXd modalAssuranceCriterion(const Eigen::Ref<const Eigen::MatrixXd>& phi,
                                        const Eigen::Ref<const Eigen::MatrixXd>& psi,
                                        const SparseMatrix& mass) {
  requireRows(phi.rows(), psi.rows(), mass.rows());
  MASTROM_REQUIRE(mass.cols() == mass.rows(), InputError, "MAC: the mass matrix is not square");
  Eigen::MatrixXd m_psi(psi.rows(), psi.cols()), m_phi(phi.rows(), phi.cols());
  m_psi.noalias() = mass * psi;
  m_phi.noalias() = mass * phi;
  Eigen::MatrixXd cross(phi.cols(), psi.cols());
  cross.noalias() = phi.transpose() * m_psi;
  const Eigen::VectorXd a = phi.cwiseProduct(m_phi).colwise().sum().transpose();
  const Eigen::VectorXd b = psi.cwiseProduct(m_psi).colwise().sum().transpose();
  return macFromProducts(cross, a, b);
}

Eigen::MatrixXd modalAssuranceCriterion(const Eigen::Ref<const Eigen::MatrixXd>& phi,
                                        const Eigen::Ref<const Eigen::MatrixXd>& psi) {
  requireRows(phi.rows(), psi.rows(), phi.rows());
  Eigen::MatrixXd cross(phi.cols(), psi.cols());
  cross.noalias() = phi.transpose() * psi;
  const Eigen::VectorXd a = phi.colwise().squaredNorm().transpose();
  const Eigen::VectorXd b = psi.colwise().squaredNorm().transpose();
  return macFromProducts(cross, a, b);
}

}  // namespace mastrom::modes
