// Peak resolution of the streaming ROM metrics (rom/model/deployment_metrics.hpp): the peaks
// of a screen at a coarse output step (PeakResolution::Continuous) against the sample maxima of a
// finely sampled deployment of the same model, for the trapezoidal law (jumps of θ̈) and the cubic
// law (jumps at the ends only, θ̈ linear in between).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "direct_modal_solve.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/parabola_polish.hpp"
#include "rom/model/peak_refinement.hpp"

namespace mastrom::rom {
namespace {

const ModalModel& scheme3Model() { return testing::coarseScheme3Model(); }

ModalDeploymentOptions optionsWithStep(double step_s, double end_time_s = 8.0) {
  ModalDeploymentOptions o;
  o.end_time_s = end_time_s;
  o.step_s = step_s;
  return o;
}

/// The peaks a screen reports, in one array: |α_z|, |r|, residual |r|, ‖F‖, |τ|.
std::vector<double> peaksOf(const fullorder::DeploymentMetrics& m) {
  return {m.peak_abs_end_angular_acceleration, m.peak_rel_end_angular_acceleration,
          m.residual_rel_end_angular_acceleration, m.peak_joint_force, m.peak_drive_torque};
}
const char* const kPeakNames[] = {"peak |alpha_z|", "peak |r|", "residual |r|", "peak |F|",
                                  "peak |tau|"};

/// Relative error bounds of the header of rom/model/deployment_metrics.hpp: the sample max at step h
/// under-reads a sinusoid of frequency ω by ≤ (ωh)²/8 of its amplitude; the polished continuous
/// max is within 0.0234 (ω_max h)⁴ (h the sub-step, ω_max h ≤ 0.3: 1.9e-4) of the true one. Taken
/// relative to the peak, as the amplitude of the top mode is at most the peak.
double sampleMaxError(const ModalModel& m, double h) {
  const double x = m.omega_rad_s.maxCoeff() * h;
  return x * x / 8.0;
}
double polishError() { return kContinuousPeakTolerance; }

struct Runs {
  fullorder::DeploymentMetrics continuous, coarse_samples, reference;
  PeakRefinementStats stats;
};

Runs runAll(const ModalModel& m, const fullorder::DriveLaw& drive, double t_d, double end_s,
            double coarse_s, double reference_s, bool coriolis = false) {
  ModalDeploymentOptions coarse = optionsWithStep(coarse_s, end_s),
                         reference = optionsWithStep(reference_s, end_s);
  coarse.coriolis_coupling = reference.coriolis_coupling = coriolis;
  const double band = fullorder::kDefaultSettlingBandRadS2;
  Runs r;
  r.continuous = modalDeploymentMetrics(m, drive, coarse, t_d, band, PeakResolution::Continuous);
  r.stats = lastPeakRefinementStats();
  r.coarse_samples = modalDeploymentMetrics(m, drive, coarse, t_d, band, PeakResolution::Samples);
  r.reference = modalDeploymentMetrics(m, drive, reference, t_d, band, PeakResolution::Samples);
  return r;
}

void printRuns(const char* what, const Runs& r, double coarse_s, double reference_s) {
  std::printf("[ measured ] %s: %ld of %ld steps refined, %ld sub-steps (at most %d per step)\n",
              what, r.stats.refined_steps, r.stats.steps, r.stats.sub_steps,
              r.stats.sub_steps_per_step);
  const std::vector<double> a = peaksOf(r.continuous), s = peaksOf(r.coarse_samples),
                            f = peaksOf(r.reference);
  for (std::size_t i = 0; i < a.size(); ++i) {
    std::printf(
        "[ measured ]   %-14s %g ms continuous %.7g (%+.4f %%), samples %.7g (%+.2f %%); "
        "%g us samples %.7g\n",
        kPeakNames[i], 1e3 * coarse_s, a[i], 100.0 * (a[i] / f[i] - 1.0), s[i],
        100.0 * (s[i] / f[i] - 1.0), 1e6 * reference_s, f[i]);
  }
}

TEST(PeakResolution, ParabolaThroughUnevenNodes) {
  // Exact on a parabola for any spacing; the even form is its h = 1 case.
  for (const double h_minus : {0.5, 1.0, 2.0}) {
    for (const double h_plus : {0.25, 1.0, 3.0}) {
      for (const double top : {-0.2, 0.0, 0.15}) {
        const auto q = [&](double x) { return 3.0 - 2.0 * (x - top) * (x - top); };
        double value = 0.0, offset = 0.0;
        ASSERT_TRUE(parabolaMaximum(q(-h_minus), q(0.0), q(h_plus), h_minus, h_plus, value, offset));
        EXPECT_NEAR(value, 3.0, 1e-13);
        EXPECT_NEAR(offset, top, 1e-13);
      }
    }
  }
  double even = 0.0, even_at = 0.0, uneven = 0.0, uneven_at = 0.0;
  ASSERT_TRUE(parabolaMaximum(0.3, 0.9, 0.5, even, even_at));
  ASSERT_TRUE(parabolaMaximum(0.3, 0.9, 0.5, 1.0, 1.0, uneven, uneven_at));
  EXPECT_DOUBLE_EQ(even, uneven);
  EXPECT_DOUBLE_EQ(even_at, uneven_at);
}

TEST(PeakResolution, PolishedMaxAcrossAChangeOfSpacing) {
  // A refined node sequence whose spacing doubles at the node next to a peak (a step refined at
  // level ℓ followed by one at ℓ − 1): a sinusoid of amplitude 1 peaking 0.4 h after the
  // junction. Read with the true spacings the polish is within the bound of the coarser spacing;
  // read as evenly spaced (before the fix) it was 1.6e-2 low.
  const double omega = 1.0, h_fine = 0.25, h_coarse = 0.5, peak_at = 0.4 * h_coarse;
  const auto v = [&](double t) { return std::cos(omega * (t - peak_at)); };
  metrics_detail::PolishedMax max;
  for (const double t : {-3.0 * h_fine, -2.0 * h_fine, -h_fine}) max.push(v(t), h_fine);
  max.push(v(0.0), h_fine);
  for (const double t : {h_coarse, 2.0 * h_coarse, 3.0 * h_coarse}) max.push(v(t), h_coarse);
  std::printf("[ measured ] polished max across the spacing change: 1 %+.2e\n", max.max() - 1.0);
  EXPECT_LE(max.max(), 1.0 + 1e-15);
  EXPECT_GE(max.max(), 1.0 - rom::polishError(omega * h_coarse));
}

TEST(PeakResolution, CoarseStepPeaksMatchAFinelySampledDeployment) {
  // The paper's drives over the full 8 s record: 1 ms output step against 10 µs; the cycloidal
  // law (θ̈ continuous) as the smooth case, where the peaks rise slowly over many steps.
  const ModalModel& m = scheme3Model();
  const double fine_error = sampleMaxError(m, 1e-5);
  std::printf(
      "[ measured ] coarse Scheme 3: %d modes, f_max = %.0f Hz; 10 us samples under-read "
      "by <= %.2e, polish %.2e\n",
      m.modeCount(), m.omega_rad_s.maxCoeff() / (2.0 * M_PI), fine_error, polishError());
  for (const DriveLawKind law :
       {DriveLawKind::Trapezoidal, DriveLawKind::Cubic, DriveLawKind::Cycloidal}) {
    SCOPED_TRACE(toString(law));
    fullorder::DriveLawParameters p;  // defaults: 90° in 6.1 s, ramps 0.1 s
    p.kind = law;
    const fullorder::DriveLaw drive(p);
    const Runs r = runAll(m, drive, p.duration_s, 8.0, 1e-3, 1e-5);
    printRuns(toString(law).c_str(), r, 1e-3, 1e-5);
    // The same metric continuous at 10 µs: the continuous peaks do not depend on the step.
    const fullorder::DeploymentMetrics fine_continuous =
        modalDeploymentMetrics(m, drive, optionsWithStep(1e-5), p.duration_s);
    const std::vector<double> a = peaksOf(r.continuous), s = peaksOf(r.coarse_samples),
                              f = peaksOf(r.reference), fc = peaksOf(fine_continuous);
    for (std::size_t i = 0; i < a.size(); ++i) {
      SCOPED_TRACE(kPeakNames[i]);
      // True max M: f ≤ M ≤ f (1 + fine_error) and |a − M| ≤ polish · M, M at least the settling
      // band for the peaks made of r (header: r far below the band is resolved absolutely).
      const double scale = i < 3 ? std::max(f[i], fullorder::kDefaultSettlingBandRadS2) : f[i];
      EXPECT_GE(a[i], f[i] - polishError() * scale);
      EXPECT_LE(a[i], f[i] * (1.0 + fine_error) + polishError() * scale);
      EXPECT_NEAR(a[i], fc[i], 2.0 * polishError() * scale * fc[i] / f[i]);
      EXPECT_GE(a[i], s[i]);  // a max over a superset of the samples
      // What the refinement is for: after the jumps of θ̈ the 1 ms samples miss the peaks by far
      // more than that (the cycloidal law has no jump: its samples are nearly right).
      if (law != DriveLawKind::Cycloidal) {
        EXPECT_LT(s[i], f[i] * 0.9);
      }
    }
    // The settling time of the continuous response against that of the 10 µs samples, whose
    // linear re-entry between two samples is within about one sample of the crossing (the 1 ms
    // samples: 1.7 and 3.2 ms early, a ringing peak between two samples missed). The RMS is the
    // exact integral (tests/rom/test_square_integral.cpp).
    EXPECT_EQ(r.continuous.settled, r.reference.settled);
    EXPECT_NEAR(r.continuous.settling_time, r.reference.settling_time, 2e-5);
    std::printf(
        "[ measured ]   rms %.6g at 1 ms, %.6g at 10 us (%+.3f %%); settling %.6g s, "
        "%.6g s\n",
        r.continuous.rms_rel_end_angular_acceleration, r.reference.rms_rel_end_angular_acceleration,
        100.0 * (r.continuous.rms_rel_end_angular_acceleration /
                     r.reference.rms_rel_end_angular_acceleration -
                 1.0),
        r.continuous.settling_time, r.reference.settling_time);
  }
}

TEST(PeakResolution, ShortRecordAgainstMicrosecondSamples) {
  // A compressed drive (90° in 0.4003 s: breakpoints off the 1 ms grid, so the steps they fall in
  // are split) with in-plane gravity at θ₀ = 0.3 rad, with and without the Coriolis coupling:
  // 1 ms continuous against 1 µs samples, both error bounds tight.
  ModalModel m = scheme3Model();
  m.gravity_m_s2 = Eigen::Vector3d(0.5, -9.81, 0.0);
  m.reference_angle_rad = 0.3;
  const double tolerance = sampleMaxError(m, 1e-6) + polishError();
  std::printf("[ measured ] tolerance %.2e\n", tolerance);
  for (const DriveLawKind law : {DriveLawKind::Trapezoidal, DriveLawKind::Cubic}) {
    for (const bool coriolis : {false, true}) {
      const std::string what = toString(law) + (coriolis ? " with Coriolis" : "");
      SCOPED_TRACE(what);
      const fullorder::DriveLawParameters p = testing::compressedDrive(law);
      const fullorder::DriveLaw drive(p);
      // 1 ms, and the default 0.1 ms, where consecutive steps are often refined at different
      // levels (the polish then spans unevenly spaced nodes).
      for (const double coarse : {1e-3, 1e-4}) {
        SCOPED_TRACE(coarse);
        const Runs r = runAll(m, drive, p.duration_s, 0.6, coarse, 1e-6, coriolis);
        printRuns(what.c_str(), r, coarse, 1e-6);
        const std::vector<double> a = peaksOf(r.continuous), s = peaksOf(r.coarse_samples),
                                  f = peaksOf(r.reference);
        for (std::size_t i = 0; i < a.size(); ++i) {
          EXPECT_NEAR(a[i], f[i], tolerance * f[i]) << kPeakNames[i];
          EXPECT_GE(a[i], s[i]) << kPeakNames[i];
        }
        std::printf("[ measured ]   settling %.7f s continuous, %.7f s 1 us samples\n",
                    r.continuous.settling_time, r.reference.settling_time);
        EXPECT_EQ(r.continuous.settled, r.reference.settled);
        EXPECT_NEAR(r.continuous.settling_time, r.reference.settling_time, 2e-6);
      }
    }
  }
}

}  // namespace
}  // namespace mastrom::rom
