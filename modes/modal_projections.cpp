// Per-mode quantities of the modal deployment model (see modal_projections.hpp).
#include "modes/modal_projections.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "fullorder/block_rotation.hpp"

namespace mastrom::modes {

ModalProjections projectModes(const fullorder::MultibodySystem& system, const SparseMatrix& mass,
                              const SparseMatrix& damping, const Eigen::VectorXd& q_reference,
                              const Eigen::VectorXd& omega_squared, const Eigen::MatrixXd& modes,
                              int end_body) {
  const Eigen::Index n = system.dofCount(), k = modes.cols();
  MASTROM_REQUIRE(q_reference.size() == n && modes.rows() == n && mass.rows() == n &&
                      omega_squared.size() == k &&
                      (damping.size() == 0 || damping.rows() == n),
                  InputError, "modal quantities: sizes disagree (", n, " DOFs, ", k, " modes)");
  MASTROM_REQUIRE(end_body >= -1 && end_body < system.bodyCount(), InputError,
                  "modal quantities: end_body = ", end_body, " is out of range (−1 or 0..",
                  system.bodyCount() - 1, ")");
  ModalProjections out;
  Eigen::MatrixXd m_phi(n, k);
  m_phi.noalias() = mass * modes;
  const Eigen::VectorXd omega_q = fullorder::rotationRateField(q_reference);
  const Eigen::VectorXd omega2_q = fullorder::rotationRateField(omega_q);

  out.omega_rad_s = omega_squared.cwiseMax(0.0).cwiseSqrt();
  out.rotation_participation = m_phi.transpose() * omega_q;
  out.centrifugal_participation = m_phi.transpose() * omega2_q;
  out.translation_participation.resize(3, k);
  for (int i = 0; i < 3; ++i) {
    const Eigen::VectorXd e = system.uniformField(Eigen::Vector3d::Unit(i));
    out.translation_participation.row(i) = (m_phi.transpose() * e).transpose();
  }
  Eigen::MatrixXd omega_phi(n, k);
  for (Eigen::Index j = 0; j < k; ++j)
    omega_phi.col(j) = fullorder::rotationRateField(modes.col(j));
  out.coriolis = m_phi.transpose() * omega_phi;
  out.inertia_z_kg_m2 = omega_q.dot(mass * omega_q);

  out.damping_ratio = Eigen::VectorXd::Zero(k);
  if (damping.rows() == n) {
    for (Eigen::Index j = 0; j < k; ++j) {
      const double c = modes.col(j).dot(damping * modes.col(j));
      out.damping_ratio[j] =
          out.omega_rad_s[j] > 0 ? std::max(0.0, c) / (2.0 * out.omega_rad_s[j]) : 0.0;
    }
  }

  out.end_rotation = Eigen::Matrix3Xd::Zero(3, k);
  out.end_translation = Eigen::Matrix3Xd::Zero(3, k);
  if (end_body >= 0) {
    const fullorder::RigidModule& body = system.body(end_body);
    const int offset = system.bodyDofOffset(end_body);
    const fullorder::Vec12 q_body = q_reference.segment<12>(offset);
    for (Eigen::Index j = 0; j < k; ++j) {
      const fullorder::Vec12 d_body = modes.col(j).segment<12>(offset);
      // A small rotation is an angular velocity times a unit time: the same formula.
      out.end_rotation.col(j) = body.angularVelocity(q_body, d_body);
      out.end_translation.col(j) = d_body.head<3>();
    }
  }
  return out;
}

}  // namespace mastrom::modes
