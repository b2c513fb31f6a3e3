#include "fullorder/deployment_result.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/error.hpp"
#include "fullorder/metrics_accumulator.hpp"

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

double endTangentialAcceleration(const Eigen::Vector3d& position_m,
                                 const Eigen::Vector3d& acceleration_m_s2) {
  const double r = std::hypot(position_m.x(), position_m.y());
  if (!(r > 0.0)) return 0.0;
  // t̂ = Z × p / |Z × p| = (−p_y, p_x, 0)/r.
  return (-position_m.y() * acceleration_m_s2.x() + position_m.x() * acceleration_m_s2.y()) / r;
}

std::vector<double> DeploymentSeries::endTangentialAccelerations() const {
  std::vector<double> out(end_position_m.size());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = endTangentialAcceleration(end_position_m[i], end_acceleration_m_s2[i]);
  return out;
}

DeploymentSample DeploymentSeries::sample(std::size_t i) const {
  DeploymentSample s;
  s.time_s = time_s[i];
  s.drive_angle_rad = drive_angle_rad[i];
  s.drive_rate_rad_s = drive_rate_rad_s[i];
  s.drive_acceleration_rad_s2 = drive_acceleration_rad_s2[i];
  s.end_angular_acceleration_rad_s2 = end_angular_acceleration_rad_s2[i];
  s.end_position_m = end_position_m[i];
  s.end_acceleration_m_s2 = end_acceleration_m_s2[i];
  s.joint_force_n = joint_force_n[i];
  s.joint_torque_nm = joint_torque_nm[i];
  s.newton_iterations = newton_iterations[i];
  s.constraint_residual = constraint_residual[i];
  return s;
}

void DeploymentSeries::dropFront(std::size_t n) {
  const auto drop = [n](auto& column) {
    column.erase(column.begin(),
                 column.begin() + static_cast<std::ptrdiff_t>(std::min(n, column.size())));
  };
  drop(time_s);
  drop(drive_angle_rad);
  drop(drive_rate_rad_s);
  drop(drive_acceleration_rad_s2);
  drop(end_angular_acceleration_rad_s2);
  drop(end_relative_angular_acceleration_rad_s2);
  drop(end_position_m);
  drop(end_acceleration_m_s2);
  drop(joint_force_n);
  drop(joint_torque_nm);
  drop(newton_iterations);
  drop(constraint_residual);
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

DeploymentMetrics computeMetrics(const DeploymentSeries& series, double drive_end_time_s,
                                 double settling_band_rad_s2) {
  if (series.empty()) throw UsageError("computeMetrics: the series is empty");
  series.checkConsistent();
  // The same accumulator a streaming run feeds sample by sample
  // (fullorder/metrics_accumulator.hpp).
  MetricsAccumulator accumulator(drive_end_time_s, settling_band_rad_s2);
  for (std::size_t i = 0; i < series.size(); ++i) {
    accumulator.add(series.time_s[i], series.end_relative_angular_acceleration_rad_s2[i],
                    series.end_angular_acceleration_rad_s2[i].z(), series.joint_force_n[i].norm(),
                    series.joint_torque_nm[i]);
  }
  return accumulator.metrics();
}

}  // namespace mastrom::fullorder
