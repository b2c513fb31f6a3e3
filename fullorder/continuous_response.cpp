#include "fullorder/continuous_response.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::fullorder {

namespace {

template <class T>
T combine(const std::vector<T>& column, const CubicStencil& s) {
  T v = s.weight[0] * column[static_cast<std::size_t>(s.first)];
  for (int a = 1; a < s.count; ++a) v += s.weight[a] * column[static_cast<std::size_t>(s.first + a)];
  return v;
}

/// The piece [begin, end) containing τ, by piece start times.
void pieceOf(const StepPoints& p, double tau, long& begin, long& end) {
  const std::vector<long>& starts = p.piece_starts;
  std::size_t k = 0;
  while (k + 1 < starts.size() && p.steps.time_s[static_cast<std::size_t>(starts[k + 1])] <= tau)
    ++k;
  begin = starts[k];
  end = k + 1 < starts.size() ? starts[k + 1] : static_cast<long>(p.steps.size());
}

DeploymentSample interpolate(const StepPoints& p, long begin, long end, double tau,
                             const DriveAt& drive) {
  const DeploymentSeries& s = p.steps;
  const CubicStencil st = cubicStencil(s.time_s, begin, end, tau);
  DeploymentSample out;
  out.time_s = tau;
  const DriveState d = drive(tau);
  out.drive_angle_rad = d.angle_rad;
  out.drive_rate_rad_s = d.rate_rad_s;
  out.drive_acceleration_rad_s2 = d.acceleration_rad_s2;
  out.end_angular_acceleration_rad_s2 = combine(s.end_angular_acceleration_rad_s2, st);
  out.end_position_m = combine(s.end_position_m, st);
  out.end_acceleration_m_s2 = combine(s.end_acceleration_m_s2, st);
  out.joint_force_n = combine(s.joint_force_n, st);
  out.joint_torque_nm = combine(s.joint_torque_nm, st);
  // Solver diagnostics belong to the step that reached the next step point.
  const auto it = std::lower_bound(s.time_s.begin() + begin, s.time_s.begin() + end, tau);
  const std::size_t j = std::min(static_cast<std::size_t>(it - s.time_s.begin()),
                                 static_cast<std::size_t>(end - 1));
  out.newton_iterations = s.newton_iterations[j];
  out.constraint_residual = s.constraint_residual[j];
  return out;
}

void requireUsable(const StepPoints& p) {
  MASTROM_REQUIRE(!p.steps.empty() && !p.piece_starts.empty() && p.piece_starts.front() == 0 &&
                      std::is_sorted(p.piece_starts.begin(), p.piece_starts.end()) &&
                      p.piece_starts.back() < static_cast<long>(p.steps.size()),
                  Error, "continuous response: inconsistent step points (", p.steps.size(),
                  " points, ", p.piece_starts.size(), " pieces)");
}

}  // namespace

CubicStencil cubicStencil(const std::vector<double>& t, long begin, long end, double tau) {
  CubicStencil s;
  s.count = static_cast<int>(std::min<long>(4, end - begin));
  // i: the last point at or before τ (τ past the piece's last point: extrapolation from it).
  const auto it = std::upper_bound(t.begin() + begin, t.begin() + end, tau);
  const long i = std::max(begin, static_cast<long>(it - t.begin()) - 1);
  s.first = std::clamp(i - 1, begin, end - s.count);
  for (int a = 0; a < s.count; ++a) {
    double w = 1.0;
    const double ta = t[static_cast<std::size_t>(s.first + a)];
    for (int b = 0; b < s.count; ++b) {
      if (b == a) continue;
      const double tb = t[static_cast<std::size_t>(s.first + b)];
      w *= (tau - tb) / (ta - tb);
    }
    s.weight[a] = w;
  }
  return s;
}

DeploymentSeries resampleStepPoints(const StepPoints& p, double output_step_s,
                                    const DriveAt& drive) {
  requireUsable(p);
  MASTROM_REQUIRE(std::isfinite(output_step_s) && output_step_s > 0.0, InputError,
                  "output.step = ", output_step_s, " s must be > 0");
  const DeploymentSeries& s = p.steps;
  const double t_first = s.time_s.front(), t_last = s.time_s.back();
  DeploymentSeries out;
  const long count = static_cast<long>(std::floor((t_last - t_first) / output_step_s * (1 + 1e-12)));
  out.reserve(static_cast<std::size_t>(count + 2));
  for (long k = 0; k <= count; ++k) {
    // t = k·Δ, not a running sum, so the instants are the same in every run.
    const double tau = t_first + static_cast<double>(k) * output_step_s;
    if (tau >= t_last) break;
    long begin = 0, end = 0;
    pieceOf(p, tau, begin, end);
    out.append(interpolate(p, begin, end, tau, drive));
  }
  // The last step point itself (the end of the record), exactly.
  long begin = 0, end = 0;
  pieceOf(p, t_last, begin, end);
  out.append(interpolate(p, begin, end, t_last, drive));
  return out;
}

ContinuousPeaks continuousPeaks(const StepPoints& p, double drive_end_time_s, const DriveAt& drive,
                                int subdivisions) {
  requireUsable(p);
  const DeploymentSeries& s = p.steps;
  ContinuousPeaks peaks;
  const auto visit = [&](long begin, long end, double tau) {
    const CubicStencil st = cubicStencil(s.time_s, begin, end, tau);
    const double z = combine(s.end_angular_acceleration_rad_s2, st).z();
    const double rel = z - drive(tau).acceleration_rad_s2;
    peaks.abs_end_angular_acceleration = std::max(peaks.abs_end_angular_acceleration, std::abs(z));
    peaks.rel_end_angular_acceleration =
        std::max(peaks.rel_end_angular_acceleration, std::abs(rel));
    if (tau >= drive_end_time_s) {
      peaks.residual_rel_end_angular_acceleration =
          std::max(peaks.residual_rel_end_angular_acceleration, std::abs(rel));
    }
    peaks.joint_force = std::max(peaks.joint_force, combine(s.joint_force_n, st).norm());
    peaks.drive_torque = std::max(peaks.drive_torque, std::abs(combine(s.joint_torque_nm, st)));
  };
  const std::size_t pieces = p.piece_starts.size();
  const auto timeAt = [&s](long i) { return s.time_s[static_cast<std::size_t>(i)]; };
  const auto subdivide = [&](long begin, long end, double t0, double t1) {
    for (int j = 1; j < subdivisions; ++j)
      visit(begin, end, t0 + (t1 - t0) * static_cast<double>(j) / subdivisions);
  };
  for (std::size_t k = 0; k < pieces; ++k) {
    const long begin = p.piece_starts[k];
    const long end = k + 1 < pieces ? p.piece_starts[k + 1] : static_cast<long>(s.size());
    for (long i = begin; i < end; ++i) {
      visit(begin, end, timeAt(i));
      if (i + 1 < end) subdivide(begin, end, timeAt(i), timeAt(i + 1));
    }
    // Up to the next piece's first point (a breakpoint): the left limit's side of the jump.
    if (k + 1 < pieces) subdivide(begin, end, timeAt(end - 1), timeAt(end));
  }
  return peaks;
}

void applyContinuousPeaks(const ContinuousPeaks& peaks, DeploymentMetrics& m) {
  m.peak_abs_end_angular_acceleration =
      std::max(m.peak_abs_end_angular_acceleration, peaks.abs_end_angular_acceleration);
  m.peak_rel_end_angular_acceleration =
      std::max(m.peak_rel_end_angular_acceleration, peaks.rel_end_angular_acceleration);
  m.residual_rel_end_angular_acceleration = std::max(m.residual_rel_end_angular_acceleration,
                                                     peaks.residual_rel_end_angular_acceleration);
  m.peak_joint_force = std::max(m.peak_joint_force, peaks.joint_force);
  m.peak_drive_torque = std::max(m.peak_drive_torque, peaks.drive_torque);
}

}  // namespace mastrom::fullorder
