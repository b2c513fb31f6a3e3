// The default output step (docs/theory.md §5.4a; rom/model/output_resolution.hpp,
// rom/studies/default_output_step.hpp): the step rule and its cap on their own, the excited-mode
// criterion on a two-mode model whose shares are known by hand, and Scheme 1's full order, whose
// default output, interpolated linearly, must reproduce a 1 µs output of the same run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/config.hpp"
#include "fullorder/configured_deployment.hpp"
#include "fullorder/drive_law.hpp"
#include "fullorder/run_footprint.hpp"
#include "rom/model/output_resolution.hpp"
#include "rom/studies/default_output_step.hpp"
#include "tests/rom/direct_modal_solve.hpp"

namespace mastrom::rom {
namespace {

constexpr double kPi = 3.14159265358979323846;

ModalModel twoModes(double zeta_2, double gamma_2) {
  ModalModel m;
  m.resizeModes(2, false);
  m.omega_rad_s << 2 * kPi * 1000.0, 2 * kPi * 4000.0;
  m.damping_ratio << 0.05, zeta_2;
  m.rotation_participation << 0.1, gamma_2;
  m.centrifugal_participation.setZero();
  m.end_rotation.setZero();
  m.end_rotation.row(2) << 1.0, 1.0;
  m.end_translation.setZero();
  m.momentum_participation.setZero();
  m.gravity_m_s2.setZero();
  return m;
}

TEST(OutputResolution, SharesOfTheRingingDecideWhichModeIsResolved) {
  // Ringing RMS |ψ| |Γ| a / √(4ζω): mode 1 0.1/√(0.05·1000) against mode 2 Γ₂/√(ζ₂·4000).
  const double rms1 = 0.1 / std::sqrt(0.05 * 1000.0);
  const double zeta_2 = 0.2;
  // Mode 2 just above and just below the share: the resolved mode switches between them.
  const double at_share = kRingingShare * rms1 * std::sqrt(zeta_2 * 4000.0);
  EXPECT_EQ(highestExcitedMode(twoModes(zeta_2, 1.01 * at_share), 1.0, 0.0).mode, 1);
  const ExcitedMode below = highestExcitedMode(twoModes(zeta_2, 0.99 * at_share), 1.0, 0.0);
  EXPECT_EQ(below.mode, 0);
  EXPECT_NEAR(below.frequency_hz, 1000.0, 1e-9);
  EXPECT_EQ(below.quantity, "end angular acceleration");
  // An overdamped mode does not ring, however large its share.
  EXPECT_EQ(highestExcitedMode(twoModes(1.5, 10.0), 1.0, 0.0).mode, 0);
}

TEST(OutputResolution, StepGivesTwentySamplesPerPeriodOrHonoursTheCap) {
  ExcitedMode mode{0, 1661.47, 1.0, "end angular acceleration"};
  const OutputStepChoice c = chooseOutputStep(mode, 0.5, 400.0);
  EXPECT_FALSE(c.capped);
  EXPECT_GE(c.samplesPerPeriod(), kSamplesPerPeriod);
  EXPECT_LT(c.samplesPerPeriod(), 1.25 * kSamplesPerPeriod + 1e-9);  // the series' spacing
  EXPECT_DOUBLE_EQ(c.step_s, 2.5e-5);  // 1/(20 · 1661.47) = 3.01e-5 → 2.5e-5
  // 8 s at 400 bytes per sample would be 128 MB at 2.5e-5 s: a 64 MB cap coarsens the step.
  const OutputStepChoice capped = chooseOutputStep(mode, 8.0, 400.0, 64e6);
  EXPECT_TRUE(capped.capped);
  EXPECT_LE(capped.output_bytes, 64e6);
  EXPECT_LE(capped.samples * 400.0, 64e6);
  // The finest series value that fits: 5e-5 s would be (8/5e-5 + 2) · 400 = 64.0008 MB.
  EXPECT_DOUBLE_EQ(capped.step_s, 6.25e-5);
  EXPECT_DOUBLE_EQ(capped.wanted_step_s, 2.5e-5);
  // No ringing mode: the fallback step, never coarser.
  const OutputStepChoice none = chooseOutputStep(ExcitedMode{}, 8.0, 400.0);
  EXPECT_DOUBLE_EQ(none.step_s, kFallbackOutputStepS);
  const OutputStepChoice slow = chooseOutputStep(ExcitedMode{0, 10.0, 1.0, "x"}, 8.0, 400.0);
  EXPECT_DOUBLE_EQ(slow.step_s, kFallbackOutputStepS);
}

// Scheme 1 with the paper's ramp (0.1 s at 15 °/s) cut short: 1.5° in 0.2 s, 0.25 s simulated.
Config scheme1Ramp() {
  Config c = testing::scheme1Config(10);  // Scheme 1, mesh 2 × 8, dense modal solves
  c.drive.angle_deg = 1.5;
  c.drive.duration_s = 0.2;
  c.drive.ramp_s = 0.1;
  c.simulation.end_time_s = 0.25;
  return c;
}

struct Reading {
  double peak_error = 0.0, nrmse = 0.0;
};

// The coarse output interpolated linearly onto the fine one's instants: the relative error of its
// largest |r| and the NRMSE (1.7), leaving out one coarse step either side of the drive's
// breakpoints, where r jumps with θ̈ (no sampling short of the jump's instant reproduces a jump).
Reading readThrough(const std::vector<double>& tc, const std::vector<double>& rc,
                    const fullorder::DeploymentSeries& fine, double coarse_step_s,
                    const std::vector<double>& jumps) {
  const auto& rf = fine.end_relative_angular_acceleration_rad_s2;
  double peak_c = 0.0, peak_f = 0.0, err2 = 0.0, ref2 = 0.0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < fine.time_s.size(); ++i) {
    const double t = fine.time_s[i];
    while (j + 2 < tc.size() && tc[j + 1] < t) ++j;
    const double w = std::clamp((t - tc[j]) / (tc[j + 1] - tc[j]), 0.0, 1.0);
    const double r = (1 - w) * rc[j] + w * rc[j + 1];
    peak_c = std::max(peak_c, std::abs(r));
    peak_f = std::max(peak_f, std::abs(rf[i]));
    bool near_jump = false;
    for (const double b : jumps) near_jump = near_jump || std::abs(t - b) <= coarse_step_s;
    if (near_jump) continue;
    err2 += (r - rf[i]) * (r - rf[i]);
    ref2 += rf[i] * rf[i];
  }
  return {std::abs(peak_c - peak_f) / peak_f, std::sqrt(err2 / ref2)};
}

TEST(OutputResolution, Scheme1DefaultOutputReadsLikeAFineOneOfTheSameRun) {
  Config chosen = scheme1Ramp();
  const fullorder::MastSize size = fullorder::mastSize(chosen);
  const std::optional<OutputStepChoice> choice =
      resolveFullOrderOutputStep(chosen, fullorder::resultBytesPerSample(size, true));
  ASSERT_TRUE(choice.has_value());
  ASSERT_TRUE(chosen.output.step_s.has_value());
  EXPECT_DOUBLE_EQ(*chosen.output.step_s, choice->step_s);
  EXPECT_FALSE(choice->capped);
  // At least 20 samples per period of the 1.66 kHz bending mode the drive rings (the resolved
  // mode may be a higher one: its share decides, docs/theory.md §5.4a).
  EXPECT_GE(choice->mode.frequency_hz, 1661.0);
  EXPECT_GE(1.0 / (1661.4741 * choice->step_s), kSamplesPerPeriod);
  std::printf(
      "  chosen %.3g s: mode %d at %.1f Hz (%s, share %.3g), %.1f samples/period; "
      "%.1f samples per period of 1661.5 Hz\n",
      choice->step_s, choice->mode.mode + 1, choice->mode.frequency_hz,
      choice->mode.quantity.c_str(), choice->mode.share, choice->samplesPerPeriod(),
      1.0 / (1661.4741 * choice->step_s));
  // An explicit output.step is left alone.
  Config fixed = scheme1Ramp();
  fixed.output.step_s = 1e-4;
  EXPECT_FALSE(resolveFullOrderOutputStep(fixed, 400.0).has_value());
  EXPECT_DOUBLE_EQ(*fixed.output.step_s, 1e-4);

  // One run written finely enough that every sample of the chosen step and of the old fixed
  // 0.1 ms is one of its samples: each output is the run's interpolant at its instant (§5.4), and
  // the output step does not touch the steps, so every stride of it is the output that step gives
  // (one run instead of three: the test's cost is the full order's).
  Config fine = scheme1Ramp();
  const double fine_step_s = choice->step_s / 20.0;
  const double old_stride = 1e-4 / fine_step_s;
  ASSERT_NEAR(old_stride, std::round(old_stride), 1e-6);
  fine.output.step_s = fine_step_s;
  const auto run_fine = fullorder::runConfiguredDeployment(fine);
  const auto every = [&](std::size_t stride) {
    std::pair<std::vector<double>, std::vector<double>> out;
    const auto& series = run_fine.series;
    for (std::size_t i = 0; i < series.time_s.size(); i += stride) {
      out.first.push_back(series.time_s[i]);
      out.second.push_back(series.end_relative_angular_acceleration_rad_s2[i]);
    }
    return out;
  };
  const auto chosen_samples = every(20);
  const auto old_samples = every(static_cast<std::size_t>(std::round(old_stride)));
  EXPECT_NEAR(chosen_samples.first.back(), chosen.simulation.end_time_s, 1e-12);
  EXPECT_NEAR(old_samples.first.back(), chosen.simulation.end_time_s, 1e-12);
  const std::vector<double> jumps{0.0, 0.1, 0.2};
  const Reading at_choice = readThrough(chosen_samples.first, chosen_samples.second,
                                        run_fine.series, choice->step_s, jumps);
  const Reading at_old =
      readThrough(old_samples.first, old_samples.second, run_fine.series, 1e-4, jumps);
  std::printf(
      "  read through linear interpolation against %.3g us: chosen step peak %.3g %%, NRMSE "
      "%.3g %%; 1e-4 s peak %.3g %%, NRMSE %.3g %%\n",
      1e6 * fine_step_s, 100 * at_choice.peak_error, 100 * at_choice.nrmse, 100 * at_old.peak_error,
      100 * at_old.nrmse);
  // 20 samples per period: a sinusoid's peak read at most 1 − cos(π/20) low; the NRMSE of the
  // resolved modes at most kRingingShare, and as much again from the modes below the share.
  const double peak_tolerance = 1.0 - std::cos(kPi / kSamplesPerPeriod);
  EXPECT_LE(at_choice.peak_error, peak_tolerance);
  EXPECT_LE(at_choice.nrmse, 2.0 * kRingingShare);
  // The old fixed 0.1 ms misses both (6 samples per period): the check can fail.
  EXPECT_GT(at_old.nrmse, 2.0 * kRingingShare);
}

}  // namespace
}  // namespace mastrom::rom
