#include "fullorder/metrics_accumulator.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {

/// Fraction of the step (t_j, t_{j+1}] at which r, linear between samples, returns to the band edge
/// on the side of r_j. Requires |r_j| > band ≥ |r_{j+1}|, so the result lies in (0, 1].
double bandReentryFraction(double r_j, double r_next, double band) {
  const double side = r_j > 0.0 ? 1.0 : -1.0;
  return (std::abs(r_j) - band) / (std::abs(r_j) - side * r_next);
}

}  // namespace

MetricsAccumulator::MetricsAccumulator(double drive_end_time_s, double settling_band_rad_s2)
    : drive_end_s_(drive_end_time_s), band_(settling_band_rad_s2) {
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
  const std::size_t i = count_;
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
  if (count_ > 0 && !(t > last_t_)) {
    throw UsageError(detail::concat("deployment metrics: time ", t,
                                    " s does not exceed the previous ", last_t_, " s"));
  }
  peak_abs_ = std::max(peak_abs_, std::abs(a_z));
  peak_rel_ = std::max(peak_rel_, std::abs(r));
  peak_force_ = std::max(peak_force_, force);
  peak_torque_ = std::max(peak_torque_, std::abs(torque));
  if (t >= drive_end_s_) residual_ = std::max(residual_, std::abs(r));
  if (count_ == 0) {
    first_t_ = t;
  } else {
    // Time-weighted RMS, trapezoidal rule on r².
    square_integral_ += 0.5 * (last_r_ * last_r_ + r * r) * (t - last_t_);
  }
  if (std::abs(r) > band_) {
    any_outside_ = true;
    have_after_ = false;
    outside_t_ = t;
    outside_r_ = r;
  } else if (any_outside_ && !have_after_) {
    have_after_ = true;
    after_t_ = t;
    after_r_ = r;
  }
  last_t_ = t;
  last_r_ = r;
  ++count_;
}

DeploymentMetrics MetricsAccumulator::metrics() const {
  if (count_ == 0) throw UsageError("computeMetrics: the series is empty");
  DeploymentMetrics m;
  m.peaks_resolved = "samples";
  m.drive_end_time = drive_end_s_;
  m.settling_band = band_;
  m.peak_abs_end_angular_acceleration = peak_abs_;
  m.peak_rel_end_angular_acceleration = peak_rel_;
  m.peak_joint_force = peak_force_;
  m.peak_drive_torque = peak_torque_;
  m.residual_rel_end_angular_acceleration = residual_;
  m.rms_rel_end_angular_acceleration =
      count_ == 1 ? std::abs(last_r_) : std::sqrt(square_integral_ / (last_t_ - first_t_));

  if (last_t_ < drive_end_s_) {
    // Looking at the start-up transient only: nothing after the drive's end to measure.
    m.residual_rel_end_angular_acceleration = kNotAvailable;
    m.settling_time = kNotAvailable;
    m.settled = false;
    m.not_available = detail::concat(
        "residual_rel_end_angular_acceleration, settling_time: the record ends at t = ", last_t_,
        " s, before the drive does (", drive_end_s_, " s)");
    return m;
  }
  // Settling: the last sample outside the band decides.
  if (!any_outside_) {
    m.settled = true;
    m.settling_time = drive_end_s_;
  } else if (!have_after_) {
    m.settled = false;
    m.settling_time = last_t_;
  } else {
    const double fraction = bandReentryFraction(outside_r_, after_r_, band_);
    m.settled = true;
    m.settling_time = std::max(drive_end_s_, outside_t_ + fraction * (after_t_ - outside_t_));
  }
  return m;
}

}  // namespace mastrom::fullorder
