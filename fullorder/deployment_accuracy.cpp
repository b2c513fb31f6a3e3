#include "fullorder/deployment_accuracy.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "fullorder/metrics_accumulator.hpp"

namespace mastrom::fullorder {

DeploymentMetrics fullOrderMetrics(const DeploymentSeries& series,
                                   const DeploymentStatistics& statistics,
                                   double drive_end_time_s) {
  return fullOrderMetrics(computeMetrics(series, drive_end_time_s), statistics);
}

DeploymentMetrics fullOrderMetrics(DeploymentMetrics m, const DeploymentStatistics& statistics) {
  if (!statistics.has_continuous_peaks) return m;
  applyContinuousPeaks(statistics.continuous_peaks, m);
  m.peaks_resolved = "continuous (the full order's cubic interpolant through every step, 8 points "
                     "per step)";

  return m;
}

void estimateDiscretisationError(MastModel& model, const DeploymentOptions& options,
                                 const DeploymentSeries& series, DeploymentMetrics& metrics,
                                 const DeploymentProgress& progress) {
  estimateDiscretisationError(model, options, series.end_relative_angular_acceleration_rad_s2,
                              metrics, progress);
}

void estimateDiscretisationError(MastModel& model, const DeploymentOptions& options,
                                 const std::vector<double>& relative_rad_s2,
                                 DeploymentMetrics& metrics, const DeploymentProgress& progress) {
  MASTROM_REQUIRE(options.adaptive, InputError,
                  "the discretisation error is estimated for adaptive steps only "
                  "(simulation.adaptive = true)");
  constexpr double kLooser = 8.0;  // error ratio kLooser^(2/3) = 4
  DeploymentOptions looser = options;
  looser.step_control.tolerance = std::min(0.1, kLooser * options.step_control.tolerance);
  // The steps no estimate judges scale as the judged ones: the first steps and the cap (with the
  // cap, the ladder max_step · 2^(−k) of step sizes keeps its levels).
  const double coarser =
      looserStepFactor(options.step_control.tolerance, looser.step_control.tolerance);
  looser.step_control.initial_step_s *= coarser;
  looser.step_control.max_step_s *= coarser;
  looser.checkpoint_sink = nullptr;
  looser.checkpoint_every_s = 0.0;
  looser.checkpoint_every_steps = 0;
  // The second run is compared sample by sample as it goes and keeps no series: the estimate
  // holds the first run's r (8 bytes an output instant) and nothing that grows with the horizon.
  const std::size_t n = relative_rad_s2.size();
  std::size_t count = 0;
  double d2 = 0.0, r2 = 0.0;
  MetricsAccumulator looser_samples(metrics.drive_end_time);
  looser.output_sink = [&](const DeploymentSample& s) {
    looser_samples.add(s);
    if (count < n) {
      const double r = relative_rad_s2[count];
      const double d = (s.end_angular_acceleration_rad_s2.z() - s.drive_acceleration_rad_s2) - r;
      d2 += d * d;
      r2 += r * r;
    }
    ++count;
  };
  DeploymentStatistics stats;
  simulateDeployment(model, looser, &stats, progress);
  MASTROM_REQUIRE(count == n, Error, "error estimate: the second run has ", count,
                  " output instants, the first ", n);
  const DeploymentMetrics m8 = fullOrderMetrics(looser_samples.metrics(), stats);
  const double ratio = std::pow(looser.step_control.tolerance / options.step_control.tolerance,
                                2.0 / 3.0);
  const double divisor = ratio - 1.0;
  metrics.estimated_nrmse_rel_end_angular_acceleration = r2 > 0.0 ? std::sqrt(d2 / r2) / divisor : 0.0;
  const auto relative = [divisor](double looser_value, double value) {
    return value > 0.0 ? std::abs(looser_value - value) / value / divisor : 0.0;
  };
  metrics.estimated_error_peak_rel_end_angular_acceleration =
      relative(m8.peak_rel_end_angular_acceleration, metrics.peak_rel_end_angular_acceleration);
  metrics.estimated_error_peak_abs_end_angular_acceleration =
      relative(m8.peak_abs_end_angular_acceleration, metrics.peak_abs_end_angular_acceleration);
  metrics.estimated_error_peak_joint_force =
      relative(m8.peak_joint_force, metrics.peak_joint_force);
}

double looserStepFactor(double tolerance, double looser_tolerance) {
  return std::cbrt(looser_tolerance / tolerance);
}

}  // namespace mastrom::fullorder
