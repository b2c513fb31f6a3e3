#include "rom/deployment_metrics.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::rom {

fullorder::DeploymentMetrics modalDeploymentMetrics(const ModalModel& m,
                                                    const fullorder::DriveLaw& drive,
                                                    const ModalDeploymentOptions& options,
                                                    double drive_end_time_s, double band) {
  return modalDeploymentMetrics(m, sampleDrive(drive, options), options.coriolis_coupling,
                                drive_end_time_s, band);
}

fullorder::DeploymentMetrics modalDeploymentMetrics(const ModalModel& m, const SampledDrive& drive,
                                                    bool coriolis_coupling, double drive_end_time_s,
                                                    double band) {
  MASTROM_REQUIRE(std::isfinite(band) && band > 0.0, InputError, "settling band = ", band,
                  " rad/s^2; allowed: finite and > 0");
  MASTROM_REQUIRE(std::isfinite(drive_end_time_s), InputError,
                  "drive end time = ", drive_end_time_s, " s; allowed: finite");
  const ModalStepping ms = prepareModalStepping(m, drive, coriolis_coupling);
  const int k = m.modeCount();
  fullorder::DeploymentMetrics out;
  out.drive_end_time = drive_end_time_s;
  out.settling_band = band;
  // The contractions the three outputs need (rom/modal_stepping.hpp); only the x, y rows of Lη and
  // Lη̇ enter (through Z×, Z×(Z×) and the in-plane rotation of the gravity torque):
  //   η: (Lη)_x,y (0–1), Γ_cᵀη (2), pad;  η̇: (Lη̇)_x,y (0–1), Γ_cᵀη̇ (2), pad;
  //   η̈: (ψη̈)_z (0), Lη̈ (1–3), Γᵀη̈ (4), pad.
  StateContraction<4, 4, 6> w(k);
  w.eta.topRows<2>() = w.rate.topRows<2>() = m.momentum_participation.topRows<2>();
  w.eta.row(2) = w.rate.row(2) = m.centrifugal_participation.transpose();
  w.acc.row(0) = m.end_rotation.row(2);
  w.acc.middleRows<3>(1) = m.momentum_participation;
  w.acc.row(4) = m.rotation_participation.transpose();
  const double m_tot = m.total_mass_kg;
  const Eigen::Vector3d first_moment_ref = m_tot * m.centroid_m;
  const Eigen::Vector3d& g = m.gravity_m_s2;
  // Running reductions (computeMetrics' definitions).
  double t_first = 0.0, t_prev = 0.0, r_prev = 0.0, integral = 0.0, peak_force2 = 0.0;
  long samples = 0;
  bool outside = false, have_next = false;  // last sample outside the band, and the one after it
  double t_out = 0.0, r_out = 0.0, t_next = 0.0, r_next = 0.0;
  runModalStepping(
      m, ms, drive,
      [&](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
          const Eigen::VectorXd& eta_ddot) {
        const SampledDrive::Sample& d = drive.samples[static_cast<std::size_t>(n)];
        const double t = static_cast<double>(n) * drive.step_s;
        Eigen::Vector4d y_eta, y_rate;
        Eigen::Matrix<double, 6, 1> y_acc;
        w.apply(eta, eta_dot, eta_ddot, y_eta, y_rate, y_acc);
        const double th_d = d.rate_rad_s, th_dd = d.acceleration_rad_s2;
        const double r = y_acc[0];
        const double a_z = th_dd + r;
        // In-plane parts of m c̄ + Lη and of Lη̇ (their z components drop out, see above).
        const Eigen::Vector3d moment(first_moment_ref.x() + y_eta[0],
                                     first_moment_ref.y() + y_eta[1], 0.0);
        const Eigen::Vector3d rate_moment(y_rate[0], y_rate[1], 0.0);
        const Eigen::Vector3d p_dot_rot = y_acc.segment<3>(1) + th_dd * crossZ(moment) -
                                          th_d * th_d * moment + 2.0 * th_d * crossZ(rate_moment);
        // ‖F‖² here, the square root once at the end (sqrt is monotone: the same peak).
        double force2 = 0.0, tau_gravity = 0.0;
        if (ms.gravity) {
          double c = 1.0, s = 0.0;
          ms.rotation(d.sin_angle, d.cos_angle, c, s);
          force2 = (rotateZ(c, s, p_dot_rot) - m_tot * g).squaredNorm();
          const Eigen::Vector3d moment_global = rotateZ(c, s, moment);
          tau_gravity = moment_global.x() * g.y() - moment_global.y() * g.x();
        } else {
          force2 = p_dot_rot.squaredNorm();  // a rotation keeps the length
        }
        const double torque = th_dd * (m.inertia_z_kg_m2 - 2.0 * y_eta[2]) -
                              2.0 * th_d * y_rate[2] + y_acc[4] - tau_gravity;
        MASTROM_REQUIRE(std::isfinite(r) && std::isfinite(force2) && std::isfinite(torque),
                        NumericalError, "rom deployment metrics: non-finite output at t = ", t,
                        " s");
        out.peak_abs_end_angular_acceleration =
            std::max(out.peak_abs_end_angular_acceleration, std::abs(a_z));
        out.peak_rel_end_angular_acceleration =
            std::max(out.peak_rel_end_angular_acceleration, std::abs(r));
        peak_force2 = std::max(peak_force2, force2);
        out.peak_drive_torque = std::max(out.peak_drive_torque, std::abs(torque));
        if (t >= drive_end_time_s) {
          out.residual_rel_end_angular_acceleration =
              std::max(out.residual_rel_end_angular_acceleration, std::abs(r));
        }
        if (samples == 0) {
          t_first = t;
        } else {
          integral += 0.5 * (r_prev * r_prev + r * r) * (t - t_prev);
        }
        if (std::abs(r) > band) {
          outside = true;
          have_next = false;
          t_out = t;
          r_out = r;
        } else if (outside && !have_next) {
          have_next = true;
          t_next = t;
          r_next = r;
        }
        t_prev = t;
        r_prev = r;
        ++samples;
      });
  MASTROM_REQUIRE(t_prev >= drive_end_time_s, InputError, "the record ends at t = ", t_prev,
                  " s, before the drive ends at ", drive_end_time_s,
                  " s: no residual vibration to measure (make simulation.end_time >= "
                  "drive.duration)");
  out.peak_joint_force = std::sqrt(peak_force2);
  out.rms_rel_end_angular_acceleration =
      samples == 1 ? std::abs(r_prev) : std::sqrt(integral / (t_prev - t_first));
  if (!outside) {
    out.settled = true;
    out.settling_time = drive_end_time_s;
  } else if (!have_next) {
    out.settled = false;
    out.settling_time = t_prev;
  } else {
    const double side = r_out > 0.0 ? 1.0 : -1.0;
    const double fraction = (std::abs(r_out) - band) / (std::abs(r_out) - side * r_next);
    out.settled = true;
    out.settling_time = std::max(drive_end_time_s, t_out + fraction * (t_next - t_out));
  }
  return out;
}

double peakRelativeEndAcceleration(const ModalModel& m, const fullorder::DriveLaw& drive,
                                   const ModalDeploymentOptions& options) {
  const SampledDrive sampled = sampleDrive(drive, options);
  const ModalStepping ms = prepareModalStepping(m, sampled, options.coriolis_coupling);
  const Eigen::VectorXd psi_z = m.end_rotation.row(2).transpose();
  double peak = 0.0;
  runModalStepping(
      m, ms, sampled,
      [&](long, const Eigen::VectorXd&, const Eigen::VectorXd&, const Eigen::VectorXd& eta_ddot) {
        peak = std::max(peak, std::abs(psi_z.dot(eta_ddot)));
      });
  return peak;
}

}  // namespace mastrom::rom
