// The exact ∫r² of the continuous ROM response (rom/model/square_integral.hpp), behind the RMS
// metric of rom/model/deployment_metrics.hpp: the Gramian identity on a free vibration against
// Simpson's rule on the exact response, and the RMS of a coarse-step deployment against the
// trapezoidal rule on finely sampled deployments of the same model (Richardson-extrapolated).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "direct_modal_solve.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_oscillator.hpp"
#include "rom/model/square_integral.hpp"

namespace mastrom::rom {
namespace {

const ModalModel& scheme3Model() { return testing::coarseScheme3Model(); }

ModalDeploymentOptions optionsWithStep(double step_s, double end_time_s) {
  ModalDeploymentOptions o;
  o.end_time_s = end_time_s;
  o.step_s = step_s;
  return o;
}

double meanSquare(const ModalModel& m, const fullorder::DriveLaw& drive, double t_d, double end_s,
                  double step_s, PeakResolution how) {
  const double rms =
      modalDeploymentMetrics(m, drive, optionsWithStep(step_s, end_s), t_d,
                             fullorder::kDefaultSettlingBandRadS2, how)
          .rms_rel_end_angular_acceleration;
  return rms * rms;
}

TEST(SquareIntegral, GramianGivesTheIntegralOfAFreeVibration) {
  // ∫₀^h r² of the free response from a random state = Y(x₀) − Y(x_h); the reference integrates
  // the exact response (each mode's exact map) by Simpson's rule on 2·10⁴ intervals, whose error
  // (ω_max δ)⁴/180 ≈ 1e-11 relative is far below the tolerance.
  const ModalModel& m = scheme3Model();
  fullorder::DriveLawParameters p;
  const SampledDrive drive = sampleDrive(fullorder::DriveLaw(p), optionsWithStep(1e-3, 8.0));
  const ModalStepping ms = prepareModalStepping(m, drive, false);
  ASSERT_TRUE(SquareIntegral::supported(m, ms));
  const SquareIntegral square(m, ms);
  const int k = m.modeCount();
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  Eigen::VectorXd eta(k), eta_dot(k);
  for (int i = 0; i < k; ++i) {
    eta[i] = normal(rng) / m.omega_rad_s[i];  // comparable energy in every mode
    eta_dot[i] = normal(rng);
  }
  const double h = 5e-3;
  const int intervals = 20000;
  const double delta = h / intervals;
  const Eigen::VectorXd psi = m.end_rotation.row(2).transpose();
  Eigen::VectorXd e = eta, v = eta_dot;
  double simpson = 0.0;
  for (int n = 0; n <= intervals; ++n) {
    const Eigen::ArrayXd acc = -ms.damping * v.array() - ms.stiffness * e.array();
    const double r = psi.dot(acc.matrix());
    simpson += (n == 0 || n == intervals ? 1.0 : (n % 2 == 1 ? 4.0 : 2.0)) * r * r;
    if (n == intervals) break;  // (e, v) is the state at h
    for (int i = 0; i < k; ++i) {
      const OscillatorStep s = discretizeOscillator(m.omega_rad_s[i], m.damping_ratio[i], delta);
      const Eigen::Vector2d x = advance(s, Eigen::Vector2d(e[i], v[i]), 0.0, 0.0);
      e[i] = x[0];
      v[i] = x[1];
    }
  }
  simpson *= delta / 3.0;
  const double gramian = square.freeEnergy(eta, eta_dot) - square.freeEnergy(e, v);
  std::printf("[ measured ] free vibration over %g ms: Simpson %.12g, Gramian %.12g (%.2e)\n",
              1e3 * h, simpson, gramian, gramian / simpson - 1.0);
  EXPECT_NEAR(gramian, simpson, 1e-9 * simpson);
}

/// The mean square of r by the trapezoidal rule on samples δ and δ/2, extrapolated: r jumps where
/// θ̈ does and a sample there takes the drive's value, so the rule's error is O(δ) (measured: the
/// mean square moves by 7.6e-5 relative from 10 to 5 µs and by half that from 20 to 10 µs).
double extrapolatedMeanSquare(const ModalModel& m, const fullorder::DriveLaw& drive, double t_d,
                              double end_s, double fine_s) {
  const double coarse = meanSquare(m, drive, t_d, end_s, fine_s, PeakResolution::Samples);
  const double fine = meanSquare(m, drive, t_d, end_s, 0.5 * fine_s, PeakResolution::Samples);
  return 2.0 * fine - coarse;
}

/// The continuous mean square at a coarse step differs from the exact one of the same ROM only by
/// the first-order hold of the smooth forcing (θ̇², gravity: O(Δ²), measured 1.3e-6 relative on
/// the cycloidal law at 1 ms); the extrapolated reference is within O(δ²). Both far below this.
constexpr double kMeanSquareTolerance = 2e-5;

TEST(SquareIntegral, CoarseStepRmsEqualsTheFinelySampledOne) {
  // The paper's drives over the 8 s record, 1 ms and 0.1 ms output steps against the 10/5 µs
  // samples; the 1 ms sample RMS is what the exact integral replaces.
  const ModalModel& m = scheme3Model();
  for (const DriveLawKind law :
       {DriveLawKind::Trapezoidal, DriveLawKind::Cubic, DriveLawKind::Cycloidal}) {
    SCOPED_TRACE(toString(law));
    fullorder::DriveLawParameters p;
    p.kind = law;
    const fullorder::DriveLaw drive(p);
    const double t_d = p.duration_s, end = 8.0;
    const double reference = extrapolatedMeanSquare(m, drive, t_d, end, 1e-5);
    for (const double step : {1e-3, 1e-4}) {
      const double c = meanSquare(m, drive, t_d, end, step, PeakResolution::Continuous);
      const double s = meanSquare(m, drive, t_d, end, step, PeakResolution::Samples);
      std::printf(
          "[ measured ] %s, %g ms: RMS of r continuous %.9g (%+.2e), samples %.9g (%+.2e); "
          "reference %.9g rad/s^2\n",
          toString(law).c_str(), 1e3 * step, std::sqrt(c), std::sqrt(c / reference) - 1.0,
          std::sqrt(s), std::sqrt(s / reference) - 1.0, std::sqrt(reference));
      EXPECT_NEAR(c, reference, kMeanSquareTolerance * reference) << step << " s";
      // What the integral is for: after the jumps of θ̈ the 1 ms samples are off by ≈ 1.3 %.
      if (step == 1e-3 && law != DriveLawKind::Cycloidal) {
        EXPECT_GT(std::abs(s / reference - 1.0), 100.0 * kMeanSquareTolerance);
      }
    }
  }
}

TEST(SquareIntegral, SplitStepsGravityAndTheFallbacks) {
  // A compressed drive (breakpoints off the 1 ms grid: split steps) with in-plane gravity at
  // θ₀ = 0.3 rad. With the Coriolis coupling, or an undamped mode, the Gramian does not apply and
  // the RMS stays the samples' (computeMetrics' definition).
  ModalModel m = scheme3Model();
  m.gravity_m_s2 = Eigen::Vector3d(0.5, -9.81, 0.0);
  m.reference_angle_rad = 0.3;
  for (const DriveLawKind law : {DriveLawKind::Trapezoidal, DriveLawKind::Cubic}) {
    SCOPED_TRACE(toString(law));
    const fullorder::DriveLawParameters p = testing::compressedDrive(law);
    const fullorder::DriveLaw drive(p);
    const double t_d = p.duration_s, end = 0.6;
    const double reference = extrapolatedMeanSquare(m, drive, t_d, end, 2e-6);
    const double c = meanSquare(m, drive, t_d, end, 1e-3, PeakResolution::Continuous);
    std::printf("[ measured ] %s, 0.6 s record, gravity: RMS of r at 1 ms %.9g (%+.2e)\n",
                toString(law).c_str(), std::sqrt(c), std::sqrt(c / reference) - 1.0);
    EXPECT_NEAR(c, reference, kMeanSquareTolerance * reference);

    ModalDeploymentOptions coriolis = optionsWithStep(1e-3, end);
    coriolis.coriolis_coupling = true;
    const double band = fullorder::kDefaultSettlingBandRadS2;
    EXPECT_EQ(
        modalDeploymentMetrics(m, drive, coriolis, t_d, band, PeakResolution::Continuous)
            .rms_rel_end_angular_acceleration,
        modalDeploymentMetrics(m, drive, coriolis, t_d, band, PeakResolution::Samples)
            .rms_rel_end_angular_acceleration);
    ModalModel undamped = m;
    undamped.damping_ratio[0] = 0.0;
    EXPECT_EQ(meanSquare(undamped, drive, t_d, end, 1e-3, PeakResolution::Continuous),
              meanSquare(undamped, drive, t_d, end, 1e-3, PeakResolution::Samples));
  }
}

}  // namespace
}  // namespace mastrom::rom
