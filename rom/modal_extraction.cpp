#include "rom/modal_extraction.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "common/error.hpp"

namespace mastrom::rom {

Eigen::VectorXd rotateFieldAboutZ(const Eigen::VectorXd& v) {
  Eigen::VectorXd out(v.size());
  for (Eigen::Index b = 0; b + 2 < v.size(); b += 3) {
    out[b] = -v[b + 1];  // Z × (x, y, z) = (−y, x, 0)
    out[b + 1] = v[b];
    out[b + 2] = 0.0;
  }
  return out;
}

ModalModel extractModalModel(const fullorder::MastModel& model, const LinearizedModes& lin) {
  const fullorder::MultibodySystem& sys = model.system();
  const Eigen::Index n = sys.dofCount(), k = lin.modes.cols();
  MASTROM_REQUIRE(lin.q_reference.size() == n && lin.modes.rows() == n && lin.mass.rows() == n &&
                      lin.omega_squared.size() == k && k >= 1,
                  InputError, "modal extraction: sizes disagree (", n, " DOFs, ", k, " modes)");
  const Eigen::MatrixXd m_phi = lin.mass * lin.modes;  // MΦ (n × k)
  const Eigen::VectorXd omega_q = rotateFieldAboutZ(lin.q_reference);
  const Eigen::VectorXd omega2_q = rotateFieldAboutZ(omega_q);

  ModalModel mm;
  mm.omega_rad_s = lin.omega_squared.cwiseMax(0.0).cwiseSqrt();
  mm.rotation_participation = m_phi.transpose() * omega_q;
  mm.centrifugal_participation = m_phi.transpose() * omega2_q;
  mm.momentum_participation.resize(3, k);
  for (int i = 0; i < 3; ++i) {
    const Eigen::VectorXd e = sys.uniformField(Eigen::Vector3d::Unit(i));
    mm.momentum_participation.row(i) = (m_phi.transpose() * e).transpose();
  }
  // Coriolis matrix ΦᵀMΩΦ.
  Eigen::MatrixXd omega_phi(n, k);
  for (Eigen::Index j = 0; j < k; ++j) omega_phi.col(j) = rotateFieldAboutZ(lin.modes.col(j));
  mm.coriolis = m_phi.transpose() * omega_phi;

  // Modal damping from the assembled Kelvin–Voigt matrix.
  mm.damping_ratio = Eigen::VectorXd::Zero(k);
  if (lin.damping.rows() == n) {
    for (Eigen::Index j = 0; j < k; ++j) {
      const double c = lin.modes.col(j).dot(lin.damping * lin.modes.col(j));
      mm.damping_ratio[j] = mm.omega_rad_s[j] > 0 ? std::max(0.0, c) / (2.0 * mm.omega_rad_s[j]) : 0.0;
    }
  }

  // End module: small rotation ½ Σ c × δc over the frame columns (x̂, u, v), centroid displacement
  // (the centroid r_c = A_c q, offset from r_i included).
  const int end = model.endModule();
  const fullorder::Mat3x12 centroid = sys.body(end).centroidMap();
  const int off = model.moduleDofOffset(end);
  const double d = sys.body(end).axisLength();
  const Eigen::Matrix<double, 12, 1> q_end = lin.q_reference.segment<12>(off);
  const Eigen::Vector3d cols[3] = {(q_end.segment<3>(3) - q_end.segment<3>(0)) / d,
                                   q_end.segment<3>(6), q_end.segment<3>(9)};
  mm.end_rotation.resize(3, k);
  mm.end_translation.resize(3, k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const Eigen::Matrix<double, 12, 1> phi = lin.modes.col(j).segment<12>(off);
    const Eigen::Vector3d dcols[3] = {(phi.segment<3>(3) - phi.segment<3>(0)) / d,
                                      phi.segment<3>(6), phi.segment<3>(9)};
    Eigen::Vector3d rot = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) rot += 0.5 * cols[c].cross(dcols[c]);
    mm.end_rotation.col(j) = rot;
    mm.end_translation.col(j) = centroid * phi;
  }

  // Rigid data of q̄.
  mm.inertia_z_kg_m2 = omega_q.dot(lin.mass * omega_q);
  mm.total_mass_kg = sys.totalMass();
  Eigen::Vector3d first_moment;
  for (int i = 0; i < 3; ++i)
    first_moment[i] = sys.uniformField(Eigen::Vector3d::Unit(i)).dot(lin.mass * lin.q_reference);
  mm.centroid_m = first_moment / mm.total_mass_kg;
  mm.end_position_m = centroid * q_end;
  mm.reference_angle_rad = lin.reference_angle_rad;
  mm.gravity_m_s2 = sys.gravity();
  mm.validate();
  return mm;
}

}  // namespace mastrom::rom
