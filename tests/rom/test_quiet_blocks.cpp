// Quiet blocks of the ROM metrics (rom/model/quiet_blocks.hpp, docs/theory.md §4.2c): the bounds of
// a block against the outputs of a finely sampled deployment of the same model (brute force), and
// the metrics with quiet blocks against the path that evaluates every sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "direct_modal_solve.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/peak_refinement.hpp"
#include "rom/model/quiet_blocks.hpp"

namespace mastrom::rom {
namespace {

ModalDeploymentOptions optionsWithStep(double step_s, double end_time_s) {
  ModalDeploymentOptions o;
  o.end_time_s = end_time_s;
  o.step_s = step_s;
  return o;
}

/// Restores the default (quiet blocks on) when a test ends.
struct QuietBlocksSetting {
  explicit QuietBlocksSetting(bool on) { metrics_detail::quietBlocksEnabled() = on; }
  ~QuietBlocksSetting() { metrics_detail::quietBlocksEnabled() = true; }
};

TEST(QuietBlocks, BoundsHoldOverEveryBlockAgainstFineSamples) {
  // Each block's bounds from its start state against every output of the same deployment sampled
  // 32 times finer (its forcing's first-order hold then differs from the coarse one by O(Δ²) of
  // the drive's curvature: a relative 1e-6 allowance).
  const ModalModel& m = testing::coarseScheme3Model();
  constexpr long kFine = 32;
  const double step = 2e-3, end = 1.0;
  for (const DriveLawKind law :
       {DriveLawKind::Trapezoidal, DriveLawKind::Cubic, DriveLawKind::Cycloidal}) {
    SCOPED_TRACE(toString(law));
    const fullorder::DriveLawParameters p = testing::compressedDrive(law);
    const fullorder::DriveLaw drive(p);
    const SampledDrive sampled = sampleDrive(drive, optionsWithStep(step, end));
    const ModalStepping ms = prepareModalStepping(m, sampled, false);
    ASSERT_TRUE(metrics_detail::QuietBlockBound::supported(m, ms));
    metrics_detail::QuietBlockBound bounds(m, ms, sampled);
    std::vector<metrics_detail::OutputBounds> block_bounds(sampled.blocks.size());
    std::vector<char> has_bound(sampled.blocks.size(), 0);
    runModalStepping(m, ms, sampled,
                     [&](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                         const Eigen::VectorXd&) {
                       if (n % SampledDrive::kBlockSteps != 0 || n >= sampled.steps) return;
                       const long b = n / SampledDrive::kBlockSteps;
                       has_bound[static_cast<std::size_t>(b)] =
                           bounds.bound(b, eta.data(), eta_dot.data(),
                                        block_bounds[static_cast<std::size_t>(b)]);
                     });
    const fullorder::DeploymentSeries fine =
        simulateModalDeployment(m, drive, optionsWithStep(step / kFine, end));
    long checked = 0;
    double worst = 0.0;  // largest output / its bound
    for (std::size_t b = 0; b < block_bounds.size(); ++b) {
      if (!has_bound[b]) continue;
      const metrics_detail::OutputBounds& u = block_bounds[b];
      const long first = static_cast<long>(b) * SampledDrive::kBlockSteps * kFine;
      const long last = std::min(first + SampledDrive::kBlockSteps * kFine, sampled.steps * kFine);
      for (long j = first; j <= last; ++j) {
        const std::size_t s = static_cast<std::size_t>(j);
        const double values[4] = {std::abs(fine.end_angular_acceleration_rad_s2[s].z()),
                                  std::abs(fine.end_relative_angular_acceleration_rad_s2[s]),
                                  fine.joint_force_n[s].norm(), std::abs(fine.joint_torque_nm[s])};
        const double limits[4] = {u.abs_acc, u.rel_acc, u.force, u.torque};
        for (int k = 0; k < 4; ++k) {
          EXPECT_LE(values[k], limits[k] * (1.0 + 1e-6)) << "block " << b << " output " << k;
          worst = std::max(worst, values[k] / limits[k]);
        }
        ++checked;
      }
    }
    std::printf(
        "[ measured ] %s: %ld fine samples in %ld bounded blocks of %zu; largest "
        "output / bound %.4f\n",
        toString(law).c_str(), checked,
        static_cast<long>(std::count(has_bound.begin(), has_bound.end(), 1)), block_bounds.size(),
        worst);
    EXPECT_GT(checked, 0);
  }
}

TEST(QuietBlocks, MetricsEqualThePathThatEvaluatesEverySample) {
  // The metrics with quiet blocks against the same deployment with every sample's outputs
  // evaluated (the path before the blocks): the peaks within the continuous peaks' tolerance
  // (both are maxima over refined node sets of the same continuous response), the RMS (the same
  // closed form) and the settling time to round-off; and a good share of the steps quiet, or the
  // comparison would prove nothing.
  const ModalModel& m = testing::coarseScheme3Model();
  for (const DriveLawKind law :
       {DriveLawKind::Trapezoidal, DriveLawKind::Cubic, DriveLawKind::Cycloidal}) {
    for (const double step : {2e-3, 1e-3, 3.7e-4}) {
      SCOPED_TRACE(toString(law) + " step " + std::to_string(step));
      const fullorder::DriveLawParameters p = testing::compressedDrive(law);
      const fullorder::DriveLaw drive(p);
      const ModalDeploymentOptions o = optionsWithStep(step, 1.0);
      fullorder::DeploymentMetrics every, quiet;
      long quiet_steps = 0, steps = 0;
      {
        const QuietBlocksSetting off(false);
        every = modalDeploymentMetrics(m, drive, o, p.duration_s);
      }
      quiet = modalDeploymentMetrics(m, drive, o, p.duration_s);
      quiet_steps = lastPeakRefinementStats().quiet_steps;
      steps = static_cast<long>(std::ceil(1.0 / step - 1e-9));
      const double band = fullorder::kDefaultSettlingBandRadS2;
      const double tol = kContinuousPeakTolerance;
      const auto near = [&](double a, double b, double scale) {
        return std::abs(a - b) <= tol * std::max(scale, 0.0);
      };
      EXPECT_PRED3(near, quiet.peak_abs_end_angular_acceleration,
                   every.peak_abs_end_angular_acceleration,
                   every.peak_abs_end_angular_acceleration);
      EXPECT_PRED3(near, quiet.peak_rel_end_angular_acceleration,
                   every.peak_rel_end_angular_acceleration,
                   std::max(every.peak_rel_end_angular_acceleration, band));
      EXPECT_PRED3(near, quiet.residual_rel_end_angular_acceleration,
                   every.residual_rel_end_angular_acceleration,
                   std::max(every.residual_rel_end_angular_acceleration, band));
      EXPECT_PRED3(near, quiet.peak_joint_force, every.peak_joint_force, every.peak_joint_force);
      EXPECT_PRED3(near, quiet.peak_drive_torque, every.peak_drive_torque, every.peak_drive_torque);
      EXPECT_NEAR(quiet.rms_rel_end_angular_acceleration, every.rms_rel_end_angular_acceleration,
                  1e-12 * every.rms_rel_end_angular_acceleration);
      EXPECT_EQ(quiet.settled, every.settled);
      EXPECT_NEAR(quiet.settling_time, every.settling_time, 1e-12);
      std::printf(
          "[ measured ] %s, %g ms: %ld of %ld steps quiet; peaks |r| %.9g / %.9g, "
          "F %.9g / %.9g, tau %.9g / %.9g (quiet / every sample)\n",
          toString(law).c_str(), 1e3 * step, quiet_steps, steps,
          quiet.peak_rel_end_angular_acceleration, every.peak_rel_end_angular_acceleration,
          quiet.peak_joint_force, every.peak_joint_force, quiet.peak_drive_torque,
          every.peak_drive_torque);
      EXPECT_GT(quiet_steps, steps / 4);
    }
  }
}

}  // namespace
}  // namespace mastrom::rom
