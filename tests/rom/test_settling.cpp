// The settling time of the continuous ROM response (rom/model/settling_refinement.hpp): at coarse
// output steps against the linear re-entry of microsecond samples of the same deployment.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "direct_modal_solve.hpp"
#include "rom/model/deployment_metrics.hpp"

namespace mastrom::rom {
namespace {

/// The coarse Scheme 3 of the continuous-metric tests with in-plane gravity at θ₀ = 0.3 rad.
const ModalModel& model() {
  static const ModalModel m = [] {
    ModalModel out = testing::coarseScheme3Model();
    out.gravity_m_s2 = Eigen::Vector3d(0.5, -9.81, 0.0);
    out.reference_angle_rad = 0.3;
    return out;
  }();
  return m;
}

fullorder::DeploymentMetrics run(const fullorder::DriveLaw& drive, double t_d, double end_s,
                                 double step_s, double band, PeakResolution how) {
  ModalDeploymentOptions o;
  o.end_time_s = end_s;
  o.step_s = step_s;
  return modalDeploymentMetrics(model(), drive, o, t_d, band, how);
}

TEST(ContinuousSettling, CoarseStepsAgainstMicrosecondSamples) {
  // A compressed drive (breakpoints off the grids: split steps) and bands from 2 % to 20 % of the
  // peak |r|, so that the ringing settles within the record at different instants. Reference:
  // 1 µs samples, whose linear re-entry errs by ~(ωδ)²/(8ω) ≈ 1e-9 s at these frequencies.
  for (const DriveLawKind law : {DriveLawKind::Trapezoidal, DriveLawKind::Cubic}) {
    const fullorder::DriveLawParameters p = testing::compressedDrive(law);
    const fullorder::DriveLaw drive(p);
    const double t_d = p.duration_s, end = 0.7;
    const double peak =
        run(drive, t_d, end, 1e-3, 1.0, PeakResolution::Continuous).peak_rel_end_angular_acceleration;
    for (const double share : {0.02, 0.05, 0.2}) {
      const double band = share * peak;
      const fullorder::DeploymentMetrics reference =
          run(drive, t_d, end, 1e-6, band, PeakResolution::Samples);
      ASSERT_TRUE(reference.settled);
      ASSERT_GT(reference.settling_time, t_d);
      for (const double step : {1e-3, 3.7e-4, 1e-4}) {
        SCOPED_TRACE(toString(law) + " band share " + std::to_string(share) + " step " +
                     std::to_string(step));
        const fullorder::DeploymentMetrics c =
            run(drive, t_d, end, step, band, PeakResolution::Continuous);
        const PeakRefinementStats stats = lastPeakRefinementStats();
        const fullorder::DeploymentMetrics s =
            run(drive, t_d, end, step, band, PeakResolution::Samples);
        std::printf(
            "[ measured ] %s, band %.0f %% of the peak, %g ms: settling %.7f s continuous "
            "(%+.2e s; %ld steps re-stepped, %ld sub-steps), samples %+.2e s\n",
            toString(law).c_str(), 100.0 * share, 1e3 * step, c.settling_time,
            c.settling_time - reference.settling_time, stats.settling_steps,
            stats.settling_sub_steps, s.settling_time - reference.settling_time);
        EXPECT_TRUE(c.settled);
        EXPECT_NEAR(c.settling_time, reference.settling_time, 1e-7);  // measured ≤ 1.8e-8 s
      }
    }
  }
}

TEST(ContinuousSettling, NeverLeavingTheBandAndNeverSettling) {
  // A band above every |r| after the drive: t_s = t_d; a band below the end's |r|: not settled,
  // t_s = t_end (computeMetrics' verdict).
  const fullorder::DriveLawParameters p = testing::compressedDrive(DriveLawKind::Trapezoidal);
  const fullorder::DriveLaw drive(p);
  const fullorder::DeploymentMetrics wide =
      run(drive, p.duration_s, 0.7, 1e-3, 1e6, PeakResolution::Continuous);
  EXPECT_TRUE(wide.settled);
  EXPECT_EQ(wide.settling_time, p.duration_s);
  const fullorder::DeploymentMetrics narrow =
      run(drive, p.duration_s, 0.7, 1e-3, 1e-9, PeakResolution::Continuous);
  EXPECT_FALSE(narrow.settled);
  EXPECT_NEAR(narrow.settling_time, 0.7, 1e-12);
}

}  // namespace
}  // namespace mastrom::rom
