// The ROM deployment as first written (before the stepping was reorganised for speed in
// rom/model/modal_stepping.hpp): the same exact first-order-hold stepping and output formulas of
// docs/theory.md §4.1–4.2, in the plainest form — drive law evaluated at every (one-sided) instant,
// the 2 × 2 maps applied mode by mode, each output a separate dynamic product, R from an
// angle–axis. Kept only as the independent reference the fast path is tested against
// (tests/rom/test_modal_deployment.cpp).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/drive_law.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_model.hpp"
#include "rom/model/modal_oscillator.hpp"

namespace mastrom::rom::testing {
namespace reference_detail {

inline Eigen::Matrix3d rotationZ(double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

/// Generalized modal forcing at a drive state (without the Coriolis coupling).
inline void modalForcing(const ModalModel& m, const fullorder::DriveState& d, Eigen::VectorXd& f) {
  f.noalias() = -d.acceleration_rad_s2 * m.rotation_participation;
  f.noalias() -= (d.rate_rad_s * d.rate_rad_s) * m.centrifugal_participation;
  if (!m.gravity_m_s2.isZero()) {
    // Gravity seen in the rotating frame, minus the part the preload at θ₀ already carries.
    const Eigen::Vector3d g_rot =
        rotationZ(d.angle_rad - m.reference_angle_rad).transpose() * m.gravity_m_s2;
    f.noalias() += m.momentum_participation.transpose() * (g_rot - m.gravity_m_s2);
  }
}

}  // namespace reference_detail

inline fullorder::DeploymentSeries referenceModalDeployment(const ModalModel& m,
                                                            const fullorder::DriveLaw& drive,
                                                            const ModalDeploymentOptions& options) {
  using namespace reference_detail;
  m.validate();
  MASTROM_REQUIRE(std::isfinite(options.step_s) && options.step_s > 0, InputError,
                  "rom: step = ", options.step_s, " s must be > 0");
  MASTROM_REQUIRE(std::isfinite(options.end_time_s) && options.end_time_s > 0, InputError,
                  "rom: end_time = ", options.end_time_s, " s must be > 0");
  const int k = m.modeCount();
  const double dt = options.step_s;
  const long steps = static_cast<long>(std::ceil(options.end_time_s / dt - 1e-9));

  // Exact one-step maps, once per mode.
  std::vector<OscillatorStep> maps(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i)
    maps[static_cast<std::size_t>(i)] =
        discretizeOscillator(m.omega_rad_s[i], m.damping_ratio[i], dt);

  Eigen::VectorXd eta = Eigen::VectorXd::Zero(k), eta_dot = Eigen::VectorXd::Zero(k);
  Eigen::VectorXd f_start(k), f_end(k), f_now(k), eta_ddot(k), coriolis(k);
  // With gravity and the drive at rest at t = 0, the modes start at their static deflection under
  // the gravity part of the forcing (docs/theory.md §4.1): the full forcing at θ(0) with θ̇ and θ̈
  // set to zero, over ω².
  {
    fullorder::DriveState d0 = drive.at(0.0);
    if (!m.gravity_m_s2.isZero() && d0.rate_rad_s == 0.0) {
      d0.acceleration_rad_s2 = 0.0;
      modalForcing(m, d0, f_now);
      eta = f_now.cwiseQuotient(m.omega_rad_s.cwiseAbs2());
    }
  }
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  const double m_tot = m.total_mass_kg;
  // One-sided limits: drive laws with jumps in θ̈ (trapezoidal, cubic) are right-continuous; a step
  // starts on the value after a jump and ends on the value before one.
  const double left = 1e-9 * dt;

  fullorder::DeploymentSeries series;
  series.reserve(static_cast<std::size_t>(steps + 1));
  auto record = [&](double t, const fullorder::DriveState& d, const Eigen::VectorXd& f) {
    eta_ddot = f - 2.0 * m.damping_ratio.cwiseProduct(m.omega_rad_s).cwiseProduct(eta_dot) -
               m.omega_rad_s.cwiseAbs2().cwiseProduct(eta);
    if (options.coriolis_coupling)
      eta_ddot.noalias() -= 2.0 * d.rate_rad_s * (m.coriolis * eta_dot);
    const Eigen::Matrix3d rot = rotationZ(d.angle_rad - m.reference_angle_rad);
    const double th_d = d.rate_rad_s, th_dd = d.acceleration_rad_s2;
    fullorder::DeploymentSample s;
    s.time_s = t;
    s.drive_angle_rad = d.angle_rad;
    s.drive_rate_rad_s = th_d;
    s.drive_acceleration_rad_s2 = th_dd;
    // α = θ̈ Z + R ψ η̈ + θ̇ Z × (R ψ η̇).
    const Eigen::Vector3d rel_rate = rot * (m.end_rotation * eta_dot);
    s.end_angular_acceleration_rad_s2 =
        th_dd * z + rot * (m.end_rotation * eta_ddot) + th_d * z.cross(rel_rate);
    // End centroid: p = R(p̄ + Tη); a = R[Tη̈ + θ̈ Z×p' + θ̇² Z×(Z×p') + 2θ̇ Z×Tη̇].
    const Eigen::Vector3d p_rot = m.end_position_m + m.end_translation * eta;
    s.end_position_m = rot * p_rot;
    s.end_acceleration_m_s2 = rot * (m.end_translation * eta_ddot + th_dd * z.cross(p_rot) +
                                     th_d * th_d * z.cross(z.cross(p_rot)) +
                                     2.0 * th_d * z.cross(m.end_translation * eta_dot));
    // Joint force = Ṗ − m g with P = R[θ̇ Z × (m c̄ + Lη) + Lη̇].
    const Eigen::Vector3d first_moment = m_tot * m.centroid_m + m.momentum_participation * eta;
    const Eigen::Vector3d p_dot =
        rot * (m.momentum_participation * eta_ddot + th_dd * z.cross(first_moment) +
               th_d * th_d * z.cross(z.cross(first_moment)) +
               2.0 * th_d * z.cross(m.momentum_participation * eta_dot));
    s.joint_force_n = p_dot - m_tot * m.gravity_m_s2;
    // Drive torque = Ḣ − τ_g, H = θ̇ (J − 2Γ_cᵀη) + Γᵀη̇.
    const double h_dot = th_dd * (m.inertia_z_kg_m2 - 2.0 * m.centrifugal_participation.dot(eta)) -
                         2.0 * th_d * m.centrifugal_participation.dot(eta_dot) +
                         m.rotation_participation.dot(eta_ddot);
    const double tau_gravity = (rot * first_moment).cross(m.gravity_m_s2).z();
    s.joint_torque_nm = h_dot - tau_gravity;
    s.newton_iterations = 0;
    s.constraint_residual = 0.0;
    series.append(s);
  };

  // Each step integrates the forcing between its right limit at the start and its left limit at the
  // end (first-order hold, exact for piecewise-linear forcing). A drive-law breakpoint inside a
  // step splits it, so a jump of θ̈ acts at its true instant, not smeared over the output step; one
  // within ±1e-9 Δ of a sample counts as on the grid.
  const std::vector<double> breaks = drive.breakpoints();
  std::vector<OscillatorStep> split_maps(static_cast<std::size_t>(k));
  auto subStep = [&](double ta, double tb, const std::vector<OscillatorStep>& step_maps) {
    modalForcing(m, drive.at(ta + left), f_start);
    modalForcing(m, drive.at(tb - left), f_end);
    if (options.coriolis_coupling) {
      coriolis.noalias() = m.coriolis * eta_dot;
      f_start.noalias() -= 2.0 * drive.at(ta + left).rate_rad_s * coriolis;
      f_end.noalias() -= 2.0 * drive.at(tb - left).rate_rad_s * coriolis;
    }
    for (int i = 0; i < k; ++i) {
      const Eigen::Vector2d x = advance(step_maps[static_cast<std::size_t>(i)],
                                        Eigen::Vector2d(eta[i], eta_dot[i]), f_start[i], f_end[i]);
      eta[i] = x[0];
      eta_dot[i] = x[1];
    }
  };

  const fullorder::DriveState d0 = drive.at(0.0);
  modalForcing(m, d0, f_now);
  record(0.0, d0, f_now);
  for (long step = 0; step < steps; ++step) {
    const double t0 = static_cast<double>(step) * dt, t1 = static_cast<double>(step + 1) * dt;
    double ta = t0;
    for (double tb : breaks) {
      if (tb <= ta + left || tb >= t1 - left) continue;
      for (int i = 0; i < k; ++i)
        split_maps[static_cast<std::size_t>(i)] =
            discretizeOscillator(m.omega_rad_s[i], m.damping_ratio[i], tb - ta);
      subStep(ta, tb, split_maps);
      ta = tb;
    }
    if (ta == t0) {
      subStep(t0, t1, maps);
    } else {
      for (int i = 0; i < k; ++i)
        split_maps[static_cast<std::size_t>(i)] =
            discretizeOscillator(m.omega_rad_s[i], m.damping_ratio[i], t1 - ta);
      subStep(ta, t1, split_maps);
    }
    const fullorder::DriveState d1 = drive.at(t1);
    modalForcing(m, d1, f_now);
    record(t1, d1, f_now);
  }
  return series;
}

}  // namespace mastrom::rom::testing
