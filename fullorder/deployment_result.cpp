#include "fullorder/deployment_result.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/error.hpp"

namespace mastrom::fullorder {

void DeploymentSeries::append(const DeploymentSample& sample) {
  if (!time_s.empty() && !(sample.time_s > time_s.back())) {
    throw UsageError(detail::concat("DeploymentSeries::append: time ", sample.time_s,
                                               " s does not exceed the previous ", time_s.back(),
                                               " s"));
  }
  time_s.push_back(sample.time_s);
  drive_angle_rad.push_back(sample.drive_angle_rad);
  drive_rate_rad_s.push_back(sample.drive_rate_rad_s);
  drive_acceleration_rad_s2.push_back(sample.drive_acceleration_rad_s2);
  end_angular_acceleration_rad_s2.push_back(sample.end_angular_acceleration_rad_s2);
  end_relative_angular_acceleration_rad_s2.push_back(sample.end_angular_acceleration_rad_s2.z() -
                                                     sample.drive_acceleration_rad_s2);
  end_position_m.push_back(sample.end_position_m);
  end_acceleration_m_s2.push_back(sample.end_acceleration_m_s2);
  joint_force_n.push_back(sample.joint_force_n);
  joint_torque_nm.push_back(sample.joint_torque_nm);
  newton_iterations.push_back(sample.newton_iterations);
  constraint_residual.push_back(sample.constraint_residual);
}

void DeploymentSeries::reserve(std::size_t n) {
  time_s.reserve(n);
  drive_angle_rad.reserve(n);
  drive_rate_rad_s.reserve(n);
  drive_acceleration_rad_s2.reserve(n);
  end_angular_acceleration_rad_s2.reserve(n);
  end_relative_angular_acceleration_rad_s2.reserve(n);
  end_position_m.reserve(n);
  end_acceleration_m_s2.reserve(n);
  joint_force_n.reserve(n);
  joint_torque_nm.reserve(n);
  newton_iterations.reserve(n);
  constraint_residual.reserve(n);
}

void DeploymentSeries::checkConsistent() const {
  const std::size_t n = time_s.size();
  const auto require = [n](std::size_t length, const char* name) {
    if (length != n) {
      throw UsageError(detail::concat("DeploymentSeries: column ", name, " has ",
                                                 length, " entries, time_s has ", n));
    }
  };
  require(drive_angle_rad.size(), "drive_angle_rad");
  require(drive_rate_rad_s.size(), "drive_rate_rad_s");
  require(drive_acceleration_rad_s2.size(), "drive_acceleration_rad_s2");
  require(end_angular_acceleration_rad_s2.size(), "end_angular_acceleration_rad_s2");
  require(end_relative_angular_acceleration_rad_s2.size(),
          "end_relative_angular_acceleration_rad_s2");
  require(end_position_m.size(), "end_position_m");
  require(end_acceleration_m_s2.size(), "end_acceleration_m_s2");
  require(joint_force_n.size(), "joint_force_n");
  require(joint_torque_nm.size(), "joint_torque_nm");
  require(newton_iterations.size(), "newton_iterations");
  require(constraint_residual.size(), "constraint_residual");
  for (std::size_t i = 1; i < n; ++i) {
    if (!(time_s[i] > time_s[i - 1])) {
      throw UsageError(detail::concat("DeploymentSeries: time_s[", i, "] = ", time_s[i],
                                                 " s does not exceed time_s[", i - 1,
                                                 "] = ", time_s[i - 1], " s"));
    }
  }
}

namespace {

/// NumericalError naming the column, index and time of the first non-finite value.
void requireFinite(const std::vector<double>& column, const std::vector<double>& time_s,
                   const char* name) {
  for (std::size_t i = 0; i < column.size(); ++i) {
    MASTROM_REQUIRE(std::isfinite(column[i]), NumericalError, "deployment metrics: ", name, "[", i,
                    "] = ", column[i], " at t = ", time_s[i], " s");
  }
}

/// Fraction of the step (t_j, t_{j+1}] at which r, linear between samples, returns to the band edge
/// on the side of r_j. Requires |r_j| > band ≥ |r_{j+1}|, so the result lies in (0, 1].
double bandReentryFraction(double r_j, double r_next, double band) {
  const double side = r_j > 0.0 ? 1.0 : -1.0;
  return (std::abs(r_j) - band) / (std::abs(r_j) - side * r_next);
}

}  // namespace

DeploymentMetrics computeMetrics(const DeploymentSeries& series, double drive_end_time_s,
                                 double settling_band_rad_s2) {
  if (series.empty()) throw UsageError("computeMetrics: the series is empty");
  series.checkConsistent();
  MASTROM_REQUIRE(std::isfinite(settling_band_rad_s2) && settling_band_rad_s2 > 0.0, InputError,
                  "settling band = ", settling_band_rad_s2, " rad/s^2; allowed: finite and > 0");
  MASTROM_REQUIRE(std::isfinite(drive_end_time_s), InputError,
                  "drive end time = ", drive_end_time_s, " s; allowed: finite");
  const std::vector<double>& t = series.time_s;
  const std::vector<double>& r = series.end_relative_angular_acceleration_rad_s2;
  const std::size_t n = t.size();
  requireFinite(t, t, "time_s");
  requireFinite(r, t, "end_relative_angular_acceleration_rad_s2");
  requireFinite(series.joint_torque_nm, t, "joint_torque_nm");
  DeploymentMetrics m;
  m.peaks_resolved = "samples";
  m.drive_end_time = drive_end_time_s;
  m.settling_band = settling_band_rad_s2;

  for (std::size_t i = 0; i < n; ++i) {
    const double a_z = series.end_angular_acceleration_rad_s2[i].z();
    const double force = series.joint_force_n[i].norm();
    MASTROM_REQUIRE(std::isfinite(a_z), NumericalError,
                    "deployment metrics: end_angular_acceleration_rad_s2[", i, "].z = ", a_z,
                    " at t = ", t[i], " s");
    MASTROM_REQUIRE(std::isfinite(force), NumericalError, "deployment metrics: joint_force_n[", i,
                    "] is non-finite at t = ", t[i], " s");
    m.peak_abs_end_angular_acceleration = std::max(m.peak_abs_end_angular_acceleration,
                                                   std::abs(a_z));
    m.peak_rel_end_angular_acceleration = std::max(m.peak_rel_end_angular_acceleration,
                                                   std::abs(r[i]));
    m.peak_joint_force = std::max(m.peak_joint_force, force);
    m.peak_drive_torque = std::max(m.peak_drive_torque, std::abs(series.joint_torque_nm[i]));
    if (t[i] >= drive_end_time_s) {
      m.residual_rel_end_angular_acceleration =
          std::max(m.residual_rel_end_angular_acceleration, std::abs(r[i]));
    }
  }

  // Time-weighted RMS, trapezoidal rule on r².
  if (n == 1) {
    m.rms_rel_end_angular_acceleration = std::abs(r[0]);
  } else {
    double integral = 0.0;
    for (std::size_t i = 0; i + 1 < n; ++i) {
      integral += 0.5 * (r[i] * r[i] + r[i + 1] * r[i + 1]) * (t[i + 1] - t[i]);
    }
    m.rms_rel_end_angular_acceleration = std::sqrt(integral / (t.back() - t.front()));
  }

  if (t.back() < drive_end_time_s) {
    // Looking at the start-up transient only: nothing after the drive's end to measure.
    m.residual_rel_end_angular_acceleration = kNotAvailable;
    m.settling_time = kNotAvailable;
    m.settled = false;
    m.not_available = detail::concat(
        "residual_rel_end_angular_acceleration, settling_time: the record ends at t = ", t.back(),
        " s, before the drive does (", drive_end_time_s, " s)");
    return m;
  }
  // Settling: the last sample outside the band decides.
  std::size_t last_outside = n;  // n = none
  for (std::size_t i = n; i-- > 0;) {
    if (std::abs(r[i]) > settling_band_rad_s2) {
      last_outside = i;
      break;
    }
  }
  if (last_outside == n) {
    m.settled = true;
    m.settling_time = drive_end_time_s;
  } else if (last_outside == n - 1) {
    m.settled = false;
    m.settling_time = t.back();
  } else {
    const std::size_t j = last_outside;
    const double fraction = bandReentryFraction(r[j], r[j + 1], settling_band_rad_s2);
    m.settled = true;
    m.settling_time = std::max(drive_end_time_s, t[j] + fraction * (t[j + 1] - t[j]));
  }
  return m;
}

}  // namespace mastrom::fullorder
