#include "fullorder/metrics_accumulator.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::fullorder {

MetricsAccumulator::MetricsAccumulator(double drive_end_time_s, double settling_band_rad_s2)
    : drive_end_s_(drive_end_time_s), band_(settling_band_rad_s2), history_(settling_band_rad_s2) {
  MASTROM_REQUIRE(std::isfinite(settling_band_rad_s2) && settling_band_rad_s2 > 0.0, InputError,
                  "settling band = ", settling_band_rad_s2, " rad/s^2; allowed: finite and > 0");
  MASTROM_REQUIRE(std::isfinite(drive_end_time_s), InputError,
                  "drive end time = ", drive_end_time_s, " s; allowed: finite");
}

void MetricsAccumulator::add(const DeploymentSample& s) {
  add(s.time_s, s.end_angular_acceleration_rad_s2.z() - s.drive_acceleration_rad_s2,
      s.end_angular_acceleration_rad_s2.z(), s.joint_force_n.norm(), s.joint_torque_nm);
}

void MetricsAccumulator::add(double t, double r, double a_z, double force, double torque) {
  const std::size_t i = history_.count();
  MASTROM_REQUIRE(std::isfinite(t), NumericalError, "deployment metrics: time_s[", i, "] = ", t);
  MASTROM_REQUIRE(std::isfinite(r), NumericalError,
                  "deployment metrics: end_relative_angular_acceleration_rad_s2[", i, "] = ", r,
                  " at t = ", t, " s");
  MASTROM_REQUIRE(std::isfinite(torque), NumericalError, "deployment metrics: joint_torque_nm[", i,
                  "] = ", torque, " at t = ", t, " s");
  MASTROM_REQUIRE(std::isfinite(a_z), NumericalError,
                  "deployment metrics: end_angular_acceleration_rad_s2[", i, "].z = ", a_z,
                  " at t = ", t, " s");
  MASTROM_REQUIRE(std::isfinite(force), NumericalError, "deployment metrics: joint_force_n[", i,
                  "] is non-finite at t = ", t, " s");
  if (i > 0 && !(t > history_.lastTime())) {
    throw UsageError(detail::concat("deployment metrics: time ", t,
                                    " s does not exceed the previous ", history_.lastTime(), " s"));
  }
  peak_abs_ = std::max(peak_abs_, std::abs(a_z));
  peak_rel_ = std::max(peak_rel_, std::abs(r));
  peak_force_ = std::max(peak_force_, force);
  peak_torque_ = std::max(peak_torque_, std::abs(torque));
  if (t >= drive_end_s_) residual_ = std::max(residual_, std::abs(r));
  history_.add(t, r);
}

DeploymentMetrics MetricsAccumulator::metrics() const {
  if (history_.count() == 0) throw UsageError("computeMetrics: the series is empty");
  DeploymentMetrics m;
  m.peaks_resolved = "samples";
  m.drive_end_time = drive_end_s_;
  m.settling_band = band_;
  m.peak_abs_end_angular_acceleration = peak_abs_;
  m.peak_rel_end_angular_acceleration = peak_rel_;
  m.peak_joint_force = peak_force_;
  m.peak_drive_torque = peak_torque_;
  m.residual_rel_end_angular_acceleration = residual_;
  m.rms_rel_end_angular_acceleration = history_.rms(history_.trapezoidalSquareIntegral());

  const double last_t = history_.lastTime();
  if (last_t < drive_end_s_) {
    // Looking at the start-up transient only: nothing after the drive's end to measure.
    m.residual_rel_end_angular_acceleration = kNotAvailable;
    m.settling_time = kNotAvailable;
    m.settled = false;
    m.not_available = detail::concat(
        "residual_rel_end_angular_acceleration, settling_time: the record ends at t = ", last_t,
        " s, before the drive does (", drive_end_s_, " s)");
    return m;
  }
  const SampledSettling::Settling settling = history_.settling(drive_end_s_);
  m.settled = settling.settled;
  m.settling_time = settling.time_s;
  return m;
}

}  // namespace mastrom::fullorder
