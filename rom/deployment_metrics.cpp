#include "rom/deployment_metrics.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "rom/modal_oscillator.hpp"

namespace mastrom::rom {
namespace {

/// The exact modal stepping of simulateModalDeployment; calls visit(t, drive state, η, η̇, η̈)
/// at t = 0 and at the end of every step.
template <typename Visit>
void stepModes(const ModalModel& m, const fullorder::DriveLaw& drive,
               const ModalDeploymentOptions& options, Visit visit) {
  m.validate();
  MASTROM_REQUIRE(std::isfinite(options.step_s) && options.step_s > 0, InputError,
                  "rom: step = ", options.step_s, " s must be > 0");
  MASTROM_REQUIRE(std::isfinite(options.end_time_s) && options.end_time_s > 0, InputError,
                  "rom: end_time = ", options.end_time_s, " s must be > 0");
  const int k = m.modeCount();
  const double dt = options.step_s;
  const long steps = static_cast<long>(std::ceil(options.end_time_s / dt - 1e-9));
  const double left = 1e-9 * dt;  // left limit at the end of a step (jumps in θ̈)
  std::vector<OscillatorStep> maps(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i)
    maps[i] = discretizeOscillator(m.omega_rad_s[i], m.damping_ratio[i], dt);
  const Eigen::VectorXd stiffness = m.omega_rad_s.cwiseAbs2();
  const Eigen::VectorXd damping = 2.0 * m.damping_ratio.cwiseProduct(m.omega_rad_s);
  const bool gravity = !m.gravity_m_s2.isZero();
  const auto forcing = [&](const fullorder::DriveState& d, Eigen::VectorXd& f) {
    f.noalias() = -d.acceleration_rad_s2 * m.rotation_participation;
    f.noalias() -= (d.rate_rad_s * d.rate_rad_s) * m.centrifugal_participation;
    if (gravity) {
      const Eigen::Matrix3d r =
          Eigen::AngleAxisd(d.angle_rad - m.reference_angle_rad, Eigen::Vector3d::UnitZ())
              .toRotationMatrix();
      f.noalias() +=
          m.momentum_participation.transpose() * (r.transpose() * m.gravity_m_s2 - m.gravity_m_s2);
    }
  };
  Eigen::VectorXd eta = Eigen::VectorXd::Zero(k), eta_dot = Eigen::VectorXd::Zero(k);
  Eigen::VectorXd f_now(k), f_end(k), eta_ddot(k);
  fullorder::DriveState d = drive.at(0.0);
  forcing(d, f_now);
  eta_ddot = f_now;
  visit(0.0, d, eta, eta_dot, eta_ddot);
  for (long step = 0; step < steps; ++step) {
    const double t1 = static_cast<double>(step + 1) * dt;
    // f at the start of the step is the previous end's f_now (the same drive state at the same t).
    forcing(drive.at(t1 - left), f_end);
    for (int i = 0; i < k; ++i) {
      const Eigen::Vector2d x =
          advance(maps[i], Eigen::Vector2d(eta[i], eta_dot[i]), f_now[i], f_end[i]);
      eta[i] = x[0];
      eta_dot[i] = x[1];
    }
    d = drive.at(t1);
    forcing(d, f_now);
    eta_ddot = f_now - damping.cwiseProduct(eta_dot) - stiffness.cwiseProduct(eta);
    visit(t1, d, eta, eta_dot, eta_ddot);
  }
}

}  // namespace

fullorder::DeploymentMetrics modalDeploymentMetrics(const ModalModel& m,
                                                    const fullorder::DriveLaw& drive,
                                                    const ModalDeploymentOptions& options,
                                                    double drive_end_time_s, double band) {
  if (options.coriolis_coupling) {
    return fullorder::computeMetrics(simulateModalDeployment(m, drive, options), drive_end_time_s,
                                     band);
  }
  MASTROM_REQUIRE(std::isfinite(band) && band > 0.0, InputError, "settling band = ", band,
                  " rad/s^2; allowed: finite and > 0");
  MASTROM_REQUIRE(std::isfinite(drive_end_time_s), InputError,
                  "drive end time = ", drive_end_time_s, " s; allowed: finite");
  fullorder::DeploymentMetrics out;
  out.drive_end_time = drive_end_time_s;
  out.settling_band = band;
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const Eigen::VectorXd psi_z = m.end_rotation.row(2).transpose();
  const double m_tot = m.total_mass_kg;
  const bool gravity = !m.gravity_m_s2.isZero();
  // Running reductions (computeMetrics' definitions).
  double t_first = 0.0, t_prev = 0.0, r_prev = 0.0, integral = 0.0;
  long samples = 0;
  bool outside = false, have_next = false;  // last sample outside the band, and the one after it
  double t_out = 0.0, r_out = 0.0, t_next = 0.0, r_next = 0.0;
  stepModes(m, drive, options,
            [&](double t, const fullorder::DriveState& d, const Eigen::VectorXd& eta,
                const Eigen::VectorXd& eta_dot, const Eigen::VectorXd& eta_ddot) {
              const double th_d = d.rate_rad_s, th_dd = d.acceleration_rad_s2;
              const double r = psi_z.dot(eta_ddot);
              const double a_z = th_dd + r;
              const Eigen::Vector3d moment = m_tot * m.centroid_m + m.momentum_participation * eta;
              const Eigen::Vector3d l_dot = m.momentum_participation * eta_dot;
              const Eigen::Vector3d p_dot_rot =
                  m.momentum_participation * eta_ddot + th_dd * z.cross(moment) +
                  th_d * th_d * z.cross(z.cross(moment)) + 2.0 * th_d * z.cross(l_dot);
              double force = 0.0, tau_gravity = 0.0;
              if (gravity) {
                const Eigen::Matrix3d rot =
                    Eigen::AngleAxisd(d.angle_rad - m.reference_angle_rad, z).toRotationMatrix();
                force = (rot * p_dot_rot - m_tot * m.gravity_m_s2).norm();
                tau_gravity = (rot * moment).cross(m.gravity_m_s2).z();
              } else {
                force = p_dot_rot.norm();  // a rotation keeps the length
              }
              const double torque =
                  th_dd * (m.inertia_z_kg_m2 - 2.0 * m.centrifugal_participation.dot(eta)) -
                  2.0 * th_d * m.centrifugal_participation.dot(eta_dot) +
                  m.rotation_participation.dot(eta_ddot) - tau_gravity;
              MASTROM_REQUIRE(std::isfinite(r) && std::isfinite(force) && std::isfinite(torque),
                              NumericalError,
                              "rom deployment metrics: non-finite output at t = ", t, " s");
              out.peak_abs_end_angular_acceleration =
                  std::max(out.peak_abs_end_angular_acceleration, std::abs(a_z));
              out.peak_rel_end_angular_acceleration =
                  std::max(out.peak_rel_end_angular_acceleration, std::abs(r));
              out.peak_joint_force = std::max(out.peak_joint_force, force);
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
  if (options.coriolis_coupling) {
    const fullorder::DeploymentSeries s = simulateModalDeployment(m, drive, options);
    double peak = 0.0;
    for (const double r : s.end_relative_angular_acceleration_rad_s2)
      peak = std::max(peak, std::abs(r));
    return peak;
  }
  const Eigen::VectorXd psi_z = m.end_rotation.row(2).transpose();
  double peak = 0.0;
  stepModes(m, drive, options,
            [&](double, const fullorder::DriveState&, const Eigen::VectorXd&,
                const Eigen::VectorXd&, const Eigen::VectorXd& eta_ddot) {
              peak = std::max(peak, std::abs(psi_z.dot(eta_ddot)));
            });
  return peak;
}

}  // namespace mastrom::rom
