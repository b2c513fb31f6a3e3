// Streamed outputs (fullorder/step_point_stream.hpp, metrics_accumulator.hpp, result_stream.hpp):
// * the stream's outputs and continuous peaks equal a direct evaluation of the interpolant over the
//   whole record (the algorithm before streaming, written out here as the reference: the piece of
//   each instant by its start times, the cubic through the four nearest points of the whole piece)
//   bit for bit, on synthetic step points with pieces of 1, 2, 3, 4 and many points and uneven
//   steps;
// * a deployment that streams its outputs to a sink gives the same outputs, metrics and continuous
//   peaks as one that returns them, bit for bit (adaptive and fixed steps; coarse Scheme 1);
// * the continuous RMS of α_z − θ̈ (docs/theory.md §5.4) is the exact integral of the interpolant,
//   across a jump of θ̈, where the output samples' trapezoidal rule errs by O(output.step), and a
//   deployment's RMS does not depend on its output step;
// * a result file written block by block reads back equal to the series, marked complete or, for a
//   stopped run, incomplete.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <vector>

#include "coarse_mast.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/deployment_accuracy.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/metrics_accumulator.hpp"
#include "fullorder/result_stream.hpp"
#include "fullorder/step_point_stream.hpp"

namespace mastrom::fullorder {
namespace {

DriveState driveAt(double t) {
  DriveState d;
  d.angle_rad = 0.1 * t * t;
  d.rate_rad_s = 0.2 * t;
  d.acceleration_rad_s2 = t < 0.5 ? 0.2 : -0.3;  // a jump, as at a breakpoint
  return d;
}

/// Step points with uneven steps (4 to 30 ms) and random outputs.
DeploymentSeries syntheticSteps(long count) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> step(0.004, 0.03), value(-1.0, 1.0);
  DeploymentSeries s;
  double t = 0.0;
  for (long i = 0; i < count; ++i) {
    DeploymentSample p;
    p.time_s = t;
    const DriveState d = driveAt(t);
    p.drive_angle_rad = d.angle_rad;
    p.drive_rate_rad_s = d.rate_rad_s;
    p.drive_acceleration_rad_s2 = d.acceleration_rad_s2;
    p.end_angular_acceleration_rad_s2 = {value(random), value(random),
                                         std::sin(40.0 * t) + value(random)};
    p.end_position_m = {std::cos(t), std::sin(t), value(random)};
    p.end_acceleration_m_s2 = {value(random), value(random), value(random)};
    p.joint_force_n = {value(random), value(random), value(random)};
    p.joint_torque_nm = value(random);
    p.newton_iterations = static_cast<int>(i % 5);
    p.constraint_residual = std::abs(value(random));
    s.append(p);
    t += step(random);
  }
  return s;
}

// --- the reference: the whole record at once
// --------------------------------------------------------
void pieceOf(const DeploymentSeries& s, const std::vector<long>& starts, double tau, long& begin,
             long& end) {
  std::size_t k = 0;
  while (k + 1 < starts.size() && s.time_s[static_cast<std::size_t>(starts[k + 1])] <= tau) ++k;
  begin = starts[k];
  end = k + 1 < starts.size() ? starts[k + 1] : static_cast<long>(s.size());
}

DeploymentSeries referenceResample(const DeploymentSeries& s, const std::vector<long>& starts,
                                   double step) {
  DeploymentSeries out;
  const double t_first = s.time_s.front(), t_last = s.time_s.back();
  const long count = static_cast<long>(std::floor((t_last - t_first) / step * (1 + 1e-12)));
  long begin = 0, end = 0;
  for (long k = 0; k <= count; ++k) {
    const double tau = t_first + static_cast<double>(k) * step;
    if (tau >= t_last) break;
    pieceOf(s, starts, tau, begin, end);
    out.append(interpolateInPiece(s, begin, end, tau, driveAt));
  }
  pieceOf(s, starts, t_last, begin, end);
  out.append(interpolateInPiece(s, begin, end, t_last, driveAt));
  return out;
}

ContinuousPeaks referencePeaks(const DeploymentSeries& s, const std::vector<long>& starts,
                               double drive_end) {
  ContinuousPeaks peaks;
  const int sub = 8;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    const long begin = starts[k];
    const long end = k + 1 < starts.size() ? starts[k + 1] : static_cast<long>(s.size());
    const auto t = [&s](long i) { return s.time_s[static_cast<std::size_t>(i)]; };
    const auto subdivide = [&](double t0, double t1) {
      for (int j = 1; j < sub; ++j)
        visitContinuousPeaks(s, begin, end, t0 + (t1 - t0) * static_cast<double>(j) / sub,
                             drive_end, driveAt, peaks);
    };
    for (long i = begin; i < end; ++i) {
      visitContinuousPeaks(s, begin, end, t(i), drive_end, driveAt, peaks);
      if (i + 1 < end) subdivide(t(i), t(i + 1));
    }
    if (k + 1 < starts.size()) subdivide(t(end - 1), t(end));
  }
  return peaks;
}

void expectSameSeries(const DeploymentSeries& a, const DeploymentSeries& b) {
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(a.time_s == b.time_s);
  EXPECT_TRUE(a.drive_acceleration_rad_s2 == b.drive_acceleration_rad_s2);
  EXPECT_TRUE(a.end_angular_acceleration_rad_s2 == b.end_angular_acceleration_rad_s2);
  EXPECT_TRUE(a.end_relative_angular_acceleration_rad_s2 ==
              b.end_relative_angular_acceleration_rad_s2);
  EXPECT_TRUE(a.end_position_m == b.end_position_m);
  EXPECT_TRUE(a.end_acceleration_m_s2 == b.end_acceleration_m_s2);
  EXPECT_TRUE(a.joint_force_n == b.joint_force_n);
  EXPECT_TRUE(a.joint_torque_nm == b.joint_torque_nm);
  EXPECT_TRUE(a.newton_iterations == b.newton_iterations);
  EXPECT_TRUE(a.constraint_residual == b.constraint_residual);
}

void expectSamePeaks(const ContinuousPeaks& a, const ContinuousPeaks& b) {
  EXPECT_EQ(a.abs_end_angular_acceleration, b.abs_end_angular_acceleration);
  EXPECT_EQ(a.rel_end_angular_acceleration, b.rel_end_angular_acceleration);
  EXPECT_EQ(a.residual_rel_end_angular_acceleration, b.residual_rel_end_angular_acceleration);
  EXPECT_EQ(a.joint_force, b.joint_force);
  EXPECT_EQ(a.drive_torque, b.drive_torque);
}

TEST(StepPointStream, EqualsTheWholeRecordInterpolantBitForBit) {
  // Pieces of 1, 2, 3, 4, 5 and many points; the last piece long.
  const std::vector<long> starts{0, 30, 31, 33, 36, 40, 45};
  const DeploymentSeries steps = syntheticSteps(90);
  for (double output_step : {0.0037, 0.01, 0.05}) {
    DeploymentSeries streamed;
    StepPointStream stream(output_step, 0.5, driveAt,
                           [&streamed](const DeploymentSample& s) { streamed.append(s); });
    std::size_t piece = 0;
    std::size_t largest_window = 0;
    for (std::size_t i = 0; i < steps.size(); ++i) {
      const bool starts_piece = piece < starts.size() && starts[piece] == static_cast<long>(i);
      if (starts_piece) ++piece;
      stream.add(steps.sample(i), starts_piece);
      largest_window = std::max(largest_window, stream.windowSize());
    }
    stream.finish();
    EXPECT_LE(largest_window, 4u);  // the memory does not grow with the record
    SCOPED_TRACE(output_step);
    expectSameSeries(streamed, referenceResample(steps, starts, output_step));
    expectSamePeaks(stream.peaks(), referencePeaks(steps, starts, 0.5));
  }
}

/// α_z of two cubics, one per piece either side of driveAt's jump at t = 0.5: the interpolant of
/// §5.4 reproduces each exactly, so ∫ (α_z − θ̈)² is known by brute force.
double cubicAlpha(double t) {
  return t < 0.5 ? 1.0 + 3.0 * t - 4.0 * t * t + 2.0 * t * t * t
                 : -0.5 + 2.0 * t + t * t - 1.5 * t * t * t;
}

TEST(StepPointStream, ContinuousRmsIsTheExactIntegralAcrossAJumpOfTheDrive) {
  // Uneven steps, the second piece starting at the breakpoint t = 0.5 itself.
  std::vector<double> times{0.0, 0.05, 0.13, 0.2, 0.31, 0.38, 0.47, 0.5, 0.56, 0.7, 0.74, 0.9, 1.0};
  DeploymentSeries steps;
  for (const double t : times) {
    DeploymentSample p;
    p.time_s = t;
    p.drive_acceleration_rad_s2 = driveAt(t).acceleration_rad_s2;
    p.end_angular_acceleration_rad_s2 = {0.0, 0.0, cubicAlpha(t)};
    steps.append(p);
  }
  DeploymentSeries outputs;
  StepPointStream stream(0.01, 2.0, driveAt,
                         [&outputs](const DeploymentSample& s) { outputs.append(s); });
  for (std::size_t i = 0; i < steps.size(); ++i) stream.add(steps.sample(i), i == 0 || i == 7);
  stream.finish();
  // Brute force: the midpoint rule on 2·10⁶ intervals (error ~1e-13 relative).
  const long n = 2000000;
  double brute = 0.0;
  for (long i = 0; i < n; ++i) {
    const double t = (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    const double r = cubicAlpha(t) - driveAt(t).acceleration_rad_s2;
    brute += r * r / static_cast<double>(n);
  }
  const ContinuousPeaks& peaks = stream.peaks();
  EXPECT_NEAR(peaks.square_span_s, 1.0, 1e-15);
  EXPECT_NEAR(peaks.square_rel_integral, brute, 1e-10 * brute);
  DeploymentMetrics m = computeMetrics(outputs, 2.0);
  const double sampled = m.rms_rel_end_angular_acceleration;
  applyContinuousPeaks(peaks, m);
  EXPECT_NEAR(m.rms_rel_end_angular_acceleration, std::sqrt(brute), 1e-10 * std::sqrt(brute));
  // The 0.01 s samples' trapezoidal rule straddles the jump: off by O(output step).
  EXPECT_GT(std::abs(sampled - std::sqrt(brute)), 1e-3 * std::sqrt(brute));
}

TEST(MetricsAccumulator, SampleBySampleEqualsTheWholeSeries) {
  const DeploymentSeries s = syntheticSteps(200);
  MetricsAccumulator acc(0.5, 0.3);
  for (std::size_t i = 0; i < s.size(); ++i) acc.add(s.sample(i));
  const DeploymentMetrics a = acc.metrics(), b = computeMetrics(s, 0.5, 0.3);
  EXPECT_EQ(a.rms_rel_end_angular_acceleration, b.rms_rel_end_angular_acceleration);
  EXPECT_EQ(a.settling_time, b.settling_time);
  EXPECT_EQ(a.peak_joint_force, b.peak_joint_force);
  EXPECT_EQ(a.residual_rel_end_angular_acceleration, b.residual_rel_end_angular_acceleration);
  // And against the definitions directly: the RMS by the trapezoidal rule over the record.
  double integral = 0.0;
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    const double r0 = s.end_relative_angular_acceleration_rad_s2[i];
    const double r1 = s.end_relative_angular_acceleration_rad_s2[i + 1];
    integral += 0.5 * (r0 * r0 + r1 * r1) * (s.time_s[i + 1] - s.time_s[i]);
  }
  EXPECT_NEAR(a.rms_rel_end_angular_acceleration,
              std::sqrt(integral / (s.time_s.back() - s.time_s.front())), 1e-14);
}

/// 5° in 40 ms with 10 ms ramps, 50 ms simulated (tests/fullorder/test_adaptive_deployment.cpp).
Config quickSwing(bool adaptive) {
  Config c = testing::coarseScheme1();
  c.drive.angle_deg = 5.0;
  c.drive.duration_s = 0.04;
  c.drive.ramp_s = 0.01;
  c.simulation.end_time_s = 0.05;
  c.simulation.adaptive = adaptive;
  c.simulation.time_step_s = adaptive ? 1e-5 : 1e-4;
  c.output.step_s = 1e-4;
  c.output.every = 2;
  return c;
}

TEST(StreamedDeployment, EqualsTheReturnedSeriesBitForBit) {
  for (bool adaptive : {true, false}) {
    SCOPED_TRACE(adaptive ? "adaptive" : "fixed steps");
    const Config c = quickSwing(adaptive);
    MastModel model = buildMast(mastParametersFromConfig(c));
    DeploymentOptions o = deploymentFromConfig(c);
    o.thread_tuning.enabled = false;
    DeploymentStatistics whole_stats, streamed_stats;
    const DeploymentSeries whole = simulateDeployment(model, o, &whole_stats);
    DeploymentSeries streamed;
    MetricsAccumulator accumulator(c.drive.duration_s);
    o.output_sink = [&](const DeploymentSample& s) {
      streamed.append(s);
      accumulator.add(s);
    };
    MastModel again = buildMast(mastParametersFromConfig(c));
    EXPECT_TRUE(simulateDeployment(again, o, &streamed_stats).empty());
    expectSameSeries(streamed, whole);
    EXPECT_EQ(streamed_stats.has_continuous_peaks, whole_stats.has_continuous_peaks);
    expectSamePeaks(streamed_stats.continuous_peaks, whole_stats.continuous_peaks);
    const DeploymentMetrics a = fullOrderMetrics(accumulator.metrics(), streamed_stats);
    const DeploymentMetrics b = fullOrderMetrics(whole, whole_stats, c.drive.duration_s);
    EXPECT_EQ(a.peak_rel_end_angular_acceleration, b.peak_rel_end_angular_acceleration);
    EXPECT_EQ(a.rms_rel_end_angular_acceleration, b.rms_rel_end_angular_acceleration);
    EXPECT_EQ(a.settling_time, b.settling_time);
    EXPECT_EQ(a.peak_drive_torque, b.peak_drive_torque);
  }
}

TEST(StreamedDeployment, RmsAndStepsDoNotDependOnTheOutputStep) {
  // The continuous RMS comes from the step points; the output samples' trapezoidal rule moves
  // with the output step at every jump of θ̈ (four in this drive). The steps do not land on output
  // instants, so a coarser output is every k-th sample of a finer one (§5.4).
  double rms[2], sampled[2];
  const double output_steps[2] = {1e-3, 1e-4};
  long steps[2];
  std::vector<double> r[2];
  for (int k = 0; k < 2; ++k) {
    Config c = quickSwing(true);
    c.output.step_s = output_steps[k];
    MastModel model = buildMast(mastParametersFromConfig(c));
    DeploymentOptions o = deploymentFromConfig(c);
    o.thread_tuning.enabled = false;
    DeploymentStatistics stats;
    const DeploymentSeries series = simulateDeployment(model, o, &stats);
    sampled[k] = computeMetrics(series, c.drive.duration_s).rms_rel_end_angular_acceleration;
    rms[k] = fullOrderMetrics(series, stats, c.drive.duration_s).rms_rel_end_angular_acceleration;
    steps[k] = stats.steps;
    r[k] = series.end_relative_angular_acceleration_rad_s2;
  }
  EXPECT_EQ(steps[0], steps[1]);
  ASSERT_EQ(r[1].size(), 10 * (r[0].size() - 1) + 1);
  double peak = 0.0;
  for (const double v : r[1]) peak = std::max(peak, std::abs(v));
  for (std::size_t i = 0; i < r[0].size(); ++i)  // the instants k · 1e-3 and 10k · 1e-4 may differ in their last bit
    EXPECT_NEAR(r[0][i], r[1][10 * i], 1e-12 * peak) << i;
  EXPECT_NEAR(rms[0], rms[1], 1e-12 * rms[1]);
  EXPECT_GT(std::abs(sampled[0] - rms[1]), 100.0 * std::abs(rms[0] - rms[1]));
}

TEST(StreamedDeployment, AStopRequestEndsTheRecordAtTheLastStep) {
  for (bool adaptive : {true, false}) {
    SCOPED_TRACE(adaptive ? "adaptive" : "fixed steps");
    const Config c = quickSwing(adaptive);
    MastModel model = buildMast(mastParametersFromConfig(c));
    DeploymentOptions o = deploymentFromConfig(c);
    const DeploymentSeries whole = simulateDeployment(model, o);
    DeploymentSeries streamed;
    o.output_sink = [&](const DeploymentSample& s) { streamed.append(s); };
    o.stop_requested = [&streamed] { return !streamed.empty() && streamed.time_s.back() > 0.02; };
    DeploymentStatistics stats;
    MastModel again = buildMast(mastParametersFromConfig(c));
    simulateDeployment(again, o, &stats);
    EXPECT_TRUE(stats.stopped_early);
    ASSERT_GT(streamed.size(), 10u);
    EXPECT_LT(streamed.time_s.back(), 0.03);
    // Up to the last output instant before the stop, the same values as the whole run.
    for (std::size_t i = 0; i + 1 < streamed.size(); ++i) {
      ASSERT_EQ(streamed.time_s[i], whole.time_s[i]);
      // Adaptive: the outputs within two of the longest steps (1 ms) of the stop are extrapolated
      // from the last step points, where the whole run interpolated.
      if (!adaptive || streamed.time_s[i] < streamed.time_s.back() - 2e-3) {
        EXPECT_EQ(streamed.joint_torque_nm[i], whole.joint_torque_nm[i])
            << "t = " << streamed.time_s[i];
      }
    }
  }
}

TEST(DeploymentResultStream, BlocksReadBackAsTheSeriesAndTheStopIsMarked) {
  const DeploymentSeries s = syntheticSteps(23);
  const std::string path = std::string(MASTROM_BINARY_DIR) + "/test_result_stream.h5";
  for (bool stopped : {false, true}) {
    {
      DeploymentResultStream stream(path, 0.5, 5);  // blocks of 5 rows: 4 full ones and 3 rows
      for (std::size_t i = 0; i < s.size(); ++i) stream.append(s.sample(i));
      EXPECT_EQ(stream.rows(), s.size());
      const DeploymentMetrics m = stream.sampleMetrics();
      stream.finish(m, "[mast]\nmodules = 2\n", 1.5, ResultSource::FullOrder,
                    stopped ? std::optional<double>(s.time_s.back()) : std::nullopt);
    }
    const DeploymentFile f = readDeploymentFile(path);
    expectSameSeries(f.series, s);
    EXPECT_EQ(f.complete, !stopped);
    EXPECT_EQ(f.metrics.rms_rel_end_angular_acceleration,
              computeMetrics(s, 0.5).rms_rel_end_angular_acceleration);
  }
  std::remove(path.c_str());
}

TEST(DeploymentResultStream, ANonFiniteValueLeavesNoFile) {
  const std::string path = std::string(MASTROM_BINARY_DIR) + "/test_result_stream_nan.h5";
  std::remove(path.c_str());
  {
    DeploymentResultStream stream(path, 0.5, 5);
    DeploymentSample bad;
    bad.joint_torque_nm = std::nan("");
    EXPECT_THROW(stream.append(bad), NumericalError);
  }  // destroyed without finish(): the temporary file goes too
  EXPECT_FALSE(std::ifstream(path).good());
}

}  // namespace
}  // namespace mastrom::fullorder
