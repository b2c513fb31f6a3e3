#include "fullorder/continuous_response.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "fullorder/step_point_stream.hpp"

namespace mastrom::fullorder {

namespace {

template <class T>
T combine(const std::vector<T>& column, const CubicStencil& s) {
  T v = s.weight[0] * column[static_cast<std::size_t>(s.first)];
  for (int a = 1; a < s.count; ++a) v += s.weight[a] * column[static_cast<std::size_t>(s.first + a)];
  return v;
}

void requireUsable(const StepPoints& p) {
  MASTROM_REQUIRE(!p.steps.empty() && !p.piece_starts.empty() && p.piece_starts.front() == 0 &&
                      std::is_sorted(p.piece_starts.begin(), p.piece_starts.end()) &&
                      p.piece_starts.back() < static_cast<long>(p.steps.size()),
                  Error, "continuous response: inconsistent step points (", p.steps.size(),
                  " points, ", p.piece_starts.size(), " pieces)");
}

/// Every step point through a StepPointStream: the batch functions below and a run that streams
/// its outputs share one code path, so they agree bit for bit.
ContinuousPeaks feedStepPoints(const StepPoints& p, double output_step_s, double drive_end_time_s,
                               const DriveAt& drive, StepPointStream::Emit emit,
                               int subdivisions = 8) {
  StepPointStream stream(output_step_s, drive_end_time_s, drive, std::move(emit), subdivisions);
  std::size_t piece = 0;
  for (std::size_t i = 0; i < p.steps.size(); ++i) {
    const bool starts =
        piece < p.piece_starts.size() && p.piece_starts[piece] == static_cast<long>(i);
    if (starts) ++piece;
    stream.add(p.steps.sample(i), starts);
  }
  stream.finish();
  return stream.peaks();
}

/// The Lagrange weights at τ of the stencil's points.
void setLagrangeWeights(const std::vector<double>& t, double tau, CubicStencil& s) {
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
}

}  // namespace

CubicStencil cubicStencil(const std::vector<double>& t, long begin, long end, double tau) {
  CubicStencil s;
  s.count = static_cast<int>(std::min<long>(4, end - begin));
  // i: the last point at or before τ (τ past the piece's last point: extrapolation from it).
  const auto it = std::upper_bound(t.begin() + begin, t.begin() + end, tau);
  const long i = std::max(begin, static_cast<long>(it - t.begin()) - 1);
  s.first = std::clamp(i - 1, begin, end - s.count);
  setLagrangeWeights(t, tau, s);
  return s;
}

DeploymentSample interpolateInPiece(const DeploymentSeries& s, long begin, long end, double tau,
                                    const DriveAt& drive) {
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
  const std::size_t j =
      std::min(static_cast<std::size_t>(it - s.time_s.begin()), static_cast<std::size_t>(end - 1));
  out.newton_iterations = s.newton_iterations[j];
  out.constraint_residual = s.constraint_residual[j];
  return out;
}

DeploymentSeries resampleStepPoints(const StepPoints& p, double output_step_s,
                                    const DriveAt& drive) {
  requireUsable(p);
  MASTROM_REQUIRE(std::isfinite(output_step_s) && output_step_s > 0.0, InputError,
                  "output.step = ", output_step_s, " s must be > 0");
  DeploymentSeries out;
  feedStepPoints(p, output_step_s, 0.0, drive,
                 [&out](const DeploymentSample& sample) { out.append(sample); });
  return out;
}

void visitContinuousPeaks(const DeploymentSeries& s, long begin, long end, double tau,
                          double drive_end_time_s, const DriveAt& drive, ContinuousPeaks& peaks) {
  const CubicStencil st = cubicStencil(s.time_s, begin, end, tau);
  const double z = combine(s.end_angular_acceleration_rad_s2, st).z();
  const double rel = z - drive(tau).acceleration_rad_s2;
  peaks.abs_end_angular_acceleration = std::max(peaks.abs_end_angular_acceleration, std::abs(z));
  peaks.rel_end_angular_acceleration = std::max(peaks.rel_end_angular_acceleration, std::abs(rel));
  if (tau >= drive_end_time_s) {
    peaks.residual_rel_end_angular_acceleration =
        std::max(peaks.residual_rel_end_angular_acceleration, std::abs(rel));
  }
  peaks.joint_force = std::max(peaks.joint_force, combine(s.joint_force_n, st).norm());
  peaks.drive_torque = std::max(peaks.drive_torque, std::abs(combine(s.joint_torque_nm, st)));
}

void integrateContinuousSquare(const DeploymentSeries& s, long begin, long end, double t0,
                               double t1, const DriveAt& drive, ContinuousPeaks& peaks) {
  // 4-point Gauss–Legendre: exact for r² of degree 6 (a cubic α_z less a θ̈ of degree ≤ 3 within a
  // piece of the trapezoidal and polynomial laws); the stencil is the one of the interval's middle,
  // the cubic of §5.4 for the whole interval.
  static constexpr double kNode[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                      0.8611363115940526};
  static constexpr double kWeight[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                        0.3478548451374538};
  if (!(t1 > t0)) return;
  const double half = 0.5 * (t1 - t0), middle = 0.5 * (t0 + t1);
  const CubicStencil st = cubicStencil(s.time_s, begin, end, middle);
  double sum = 0.0;
  for (int g = 0; g < 4; ++g) {
    const double tau = middle + half * kNode[g];
    CubicStencil at = st;  // the same four points, their weights at τ
    setLagrangeWeights(s.time_s, tau, at);
    const double rel =
        combine(s.end_angular_acceleration_rad_s2, at).z() - drive(tau).acceleration_rad_s2;
    sum += kWeight[g] * rel * rel;
  }
  peaks.square_rel_integral += half * sum;
  peaks.square_span_s += t1 - t0;
}

ContinuousPeaks continuousPeaks(const StepPoints& p, double drive_end_time_s, const DriveAt& drive,
                                int subdivisions) {
  requireUsable(p);
  return feedStepPoints(p, 0.0, drive_end_time_s, drive, {}, subdivisions);
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
  if (peaks.square_span_s > 0.0)
    m.rms_rel_end_angular_acceleration =
        std::sqrt(std::max(0.0, peaks.square_rel_integral) / peaks.square_span_s);
}

}  // namespace mastrom::fullorder
