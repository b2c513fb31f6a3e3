#include "rom/modal_deployment.hpp"

#include "rom/modal_stepping.hpp"

namespace mastrom::rom {

fullorder::DeploymentSeries simulateModalDeployment(const ModalModel& m,
                                                    const fullorder::DriveLaw& drive,
                                                    const ModalDeploymentOptions& options) {
  const SampledDrive sampled = sampleDrive(drive, options);
  const ModalStepping ms = prepareModalStepping(m, sampled, options.coriolis_coupling);
  const int k = m.modeCount();

  // The modal contractions every output needs, stacked so one pass over the modes per state
  // vector gives them all (derivations in rom/modal_model.hpp):
  //   η:  Tη (0–2), (Lη)_x,y (3–4), Γ_cᵀη (5)
  //   η̇:  (ψη̇)_x,y (0–1), (Tη̇)_x,y (2–3), (Lη̇)_x,y (4–5), Γ_cᵀη̇ (6), padding (7)
  //   η̈:  ψη̈ (0–2), Tη̈ (3–5), Lη̈ (6–8), Γᵀη̈ (9)
  // η̇ enters only through Z× and Lη only through Z×, Z×(Z×) and the in-plane gravity torque, so
  // their z rows are not needed.
  StateContraction<6, 8, 10> w(k);
  w.eta.middleRows<3>(0) = m.end_translation;
  w.eta.middleRows<2>(3) = m.momentum_participation.topRows<2>();
  w.eta.row(5) = m.centrifugal_participation.transpose();
  w.rate.middleRows<2>(0) = m.end_rotation.topRows<2>();
  w.rate.middleRows<2>(2) = m.end_translation.topRows<2>();
  w.rate.middleRows<2>(4) = m.momentum_participation.topRows<2>();
  w.rate.row(6) = m.centrifugal_participation.transpose();
  w.acc.middleRows<3>(0) = m.end_rotation;
  w.acc.middleRows<3>(3) = m.end_translation;
  w.acc.middleRows<3>(6) = m.momentum_participation;
  w.acc.row(9) = m.rotation_participation.transpose();
  // In-plane part (x, y, 0) of rows r, r+1 of a contraction: all that Z× and Z×(Z×) need.
  const auto planar = [](const auto& y, int r) { return Eigen::Vector3d(y[r], y[r + 1], 0.0); };

  const std::size_t samples = sampled.samples.size();
  fullorder::DeploymentSeries series;
  series.time_s.resize(samples);
  series.drive_angle_rad.resize(samples);
  series.drive_rate_rad_s.resize(samples);
  series.drive_acceleration_rad_s2.resize(samples);
  series.end_angular_acceleration_rad_s2.resize(samples);
  series.end_relative_angular_acceleration_rad_s2.resize(samples);
  series.end_position_m.resize(samples);
  series.end_acceleration_m_s2.resize(samples);
  series.joint_force_n.resize(samples);
  series.joint_torque_nm.resize(samples);
  series.newton_iterations.assign(samples, 0);
  series.constraint_residual.assign(samples, 0.0);

  const double m_tot = m.total_mass_kg;
  const Eigen::Vector3d first_moment_ref = m_tot * m.centroid_m;
  const Eigen::Vector3d& g = m.gravity_m_s2;
  runModalStepping(
      m, ms, sampled,
      [&](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
          const Eigen::VectorXd& eta_ddot) {
        const auto i = static_cast<std::size_t>(n);
        const SampledDrive::Sample& d = sampled.samples[i];
        Eigen::Matrix<double, 6, 1> y_eta;
        Eigen::Matrix<double, 8, 1> y_rate;
        Eigen::Matrix<double, 10, 1> y_acc;
        w.apply(eta, eta_dot, eta_ddot, y_eta, y_rate, y_acc);
        double c = 1.0, s = 0.0;
        ms.rotation(d.sin_angle, d.cos_angle, c, s);
        const double th_d = d.rate_rad_s, th_dd = d.acceleration_rad_s2, th_d2 = th_d * th_d;
        series.time_s[i] = static_cast<double>(n) * sampled.step_s;
        series.drive_angle_rad[i] = d.angle_rad;
        series.drive_rate_rad_s[i] = th_d;
        series.drive_acceleration_rad_s2[i] = th_dd;
        // α = θ̈ Z + R ψ η̈ + θ̇ Z × (R ψ η̇) = θ̈ Z + R (ψη̈ + θ̇ Z × ψη̇)  (R commutes with Z×).
        Eigen::Vector3d alpha = rotateZ(c, s, y_acc.head<3>() + th_d * crossZ(planar(y_rate, 0)));
        alpha.z() += th_dd;
        series.end_angular_acceleration_rad_s2[i] = alpha;
        series.end_relative_angular_acceleration_rad_s2[i] = y_acc[2];  // (ψη̈)_z, R keeps z
        // End centroid: p = R(p̄ + Tη); a = R[Tη̈ + θ̈ Z×p' + θ̇² Z×(Z×p') + 2θ̇ Z×Tη̇],
        // Z×(Z×v) = −(v_x, v_y, 0).
        const Eigen::Vector3d p_rot = m.end_position_m + y_eta.segment<3>(0);
        series.end_position_m[i] = rotateZ(c, s, p_rot);
        series.end_acceleration_m_s2[i] =
            rotateZ(c, s,
                    y_acc.segment<3>(3) + th_dd * crossZ(p_rot) -
                        th_d2 * Eigen::Vector3d(p_rot.x(), p_rot.y(), 0.0) +
                        2.0 * th_d * crossZ(planar(y_rate, 2)));
        // Joint force = Ṗ − m g with P = R[θ̇ Z × (m c̄ + Lη) + Lη̇].
        // (m c̄ + Lη)_z enters no output (Z× and the in-plane gravity torque drop it).
        const Eigen::Vector3d moment = planar(first_moment_ref, 0) + planar(y_eta, 3);
        const Eigen::Vector3d p_dot =
            rotateZ(c, s,
                    y_acc.segment<3>(6) + th_dd * crossZ(moment) -
                        th_d2 * Eigen::Vector3d(moment.x(), moment.y(), 0.0) +
                        2.0 * th_d * crossZ(planar(y_rate, 4)));
        series.joint_force_n[i] = p_dot - m_tot * g;
        // Drive torque = Ḣ − τ_g, H = θ̇ (J − 2Γ_cᵀη) + Γᵀη̇, τ_g = ((R s) × g)_z.
        const double h_dot =
            th_dd * (m.inertia_z_kg_m2 - 2.0 * y_eta[5]) - 2.0 * th_d * y_rate[6] + y_acc[9];
        const Eigen::Vector3d moment_global = rotateZ(c, s, moment);
        series.joint_torque_nm[i] = h_dot - (moment_global.x() * g.y() - moment_global.y() * g.x());
      });
  return series;
}

}  // namespace mastrom::rom
