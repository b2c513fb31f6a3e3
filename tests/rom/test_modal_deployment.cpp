// ROM deployment (docs/theory.md §4.1): a one-mode model against the closed-form response, the ROM
// of a coarse Scheme 1 mast against the nonlinear full-order integrator on the same case, and the
// fast stepping (rom/model/modal_stepping.hpp) against the plain first implementation
// (reference_modal_deployment.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/mast_config.hpp"
#include "modes/eigen_solver.hpp"
#include "reference_modal_deployment.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_extraction.hpp"
#include "rom_fixtures.hpp"

namespace mastrom::rom {
namespace {

ModalModel oneMode(double omega, double gamma, double psi_z) {
  ModalModel m;
  m.omega_rad_s = Eigen::VectorXd::Constant(1, omega);
  m.damping_ratio = Eigen::VectorXd::Zero(1);
  m.rotation_participation = Eigen::VectorXd::Constant(1, gamma);
  m.centrifugal_participation = Eigen::VectorXd::Zero(1);
  m.end_rotation = Eigen::Vector3d(0, 0, psi_z);
  m.end_translation = Eigen::Vector3d::Zero();
  m.momentum_participation = Eigen::Vector3d::Zero();
  m.coriolis = Eigen::MatrixXd::Zero(1, 1);
  m.inertia_z_kg_m2 = 0.3;
  m.total_mass_kg = 2.0;
  m.centroid_m = Eigen::Vector3d(0.2, 0, 0);
  m.end_position_m = Eigen::Vector3d(0.45, 0, 0);
  return m;
}

TEST(ModalDeployment, OneModeRespondsToTheRampLikeTheClosedForm) {
  // During the trapezoidal ramp θ̈ = a is constant: η = −Γa/ω² (1 − cos ωt), so the relative end
  // angular acceleration is ψ_z η̈ = −ψ_z Γ a cos ωt and the torque Jθ̈ + Γη̈ = Ja − Γ²a cos ωt.
  const double w = 2 * M_PI * 50.0, gamma = 0.05, psi = 1.7;
  const ModalModel m = oneMode(w, gamma, psi);
  fullorder::DriveLawParameters dp;
  dp.duration_s = 1.0;
  dp.ramp_s = 0.2;
  dp.total_angle_rad = 0.5;
  const fullorder::DriveLaw drive(dp);
  const double a = drive.at(0.1).acceleration_rad_s2;
  ModalDeploymentOptions o;
  o.end_time_s = 0.19;
  o.step_s = 1e-3;
  const fullorder::DeploymentSeries s = simulateModalDeployment(m, drive, o);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double t = s.time_s[i];
    EXPECT_NEAR(s.end_relative_angular_acceleration_rad_s2[i], -psi * gamma * a * std::cos(w * t),
                1e-10 * psi * gamma * a);
    EXPECT_NEAR(s.joint_torque_nm[i], 0.3 * a - gamma * gamma * a * std::cos(w * t), 1e-10 * a);
    // No elastic translation: the joint force is the rigid m (θ̈ Z × c − θ̇² c).
    const double th = s.drive_angle_rad[i], wd = s.drive_rate_rad_s[i];
    const Eigen::Vector3d c = 0.2 * Eigen::Vector3d(std::cos(th), std::sin(th), 0);
    const Eigen::Vector3d f = 2.0 * (a * Eigen::Vector3d(-c.y(), c.x(), 0) - wd * wd * c);
    EXPECT_LT((s.joint_force_n[i] - f).norm(), 1e-10 * f.norm() + 1e-14);
  }
}

/// ROM of a locked coarse Scheme 1 mast, by a dense modal solve of its tangent (θ₀ = 0, no
/// gravity).
struct Scheme1Case {
  Config config;
  fullorder::MastModel driven;
  ModalModel rom;
};

Scheme1Case buildScheme1(int modes) {
  Config c;
  c.mast.modules = 2;
  c.interface.elements_axial = 1;
  c.interface.elements_circumferential = 6;
  c.drive.angle_deg = 10.0;  // compressed drive: the test's horizon stays short
  c.drive.duration_s = 0.04;
  c.drive.ramp_s = 0.01;
  fullorder::MastParameters p = fullorder::mastParametersFromConfig(c);
  fullorder::MastParameters pl = p;
  pl.lock_angle_rad = 0.0;
  const fullorder::MastModel locked = fullorder::buildMast(pl);
  const fullorder::MultibodySystem& sys = locked.system();
  const int n = sys.dofCount(), nc = sys.constraintCount();
  const Eigen::VectorXd q = sys.referenceCoordinates(), zero = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd lambda = Eigen::VectorXd::Zero(nc);
  modes::SparseMatrix hk, hc;
  sys.assembleIterationMatrix(q, zero, lambda, 0.0, {0, 0, 1, 1}, hk);
  sys.assembleIterationMatrix(q, zero, lambda, 0.0, {0, 1, 0, 1}, hc);
  modes::ConstrainedEigenproblem prob;
  prob.stiffness = hk.topLeftCorner(n, n);
  prob.mass = sys.massMatrix();
  prob.constraint_jacobian = hk.bottomLeftCorner(nc, n);
  modes::EigenSolverOptions eo;
  eo.count = modes;
  eo.backend = EigenBackendKind::Dense;
  const modes::EigenResult res = modes::solveConstrainedEigenproblem(prob, eo);
  EXPECT_TRUE(res.ok()) << res.message;
  LinearizedModes lin;
  lin.q_reference = q;
  lin.mass = sys.massMatrix();
  lin.damping = hc.topLeftCorner(n, n);
  lin.omega_squared = res.eigenvalues_rad2_s2;
  lin.modes = res.modes;
  fullorder::MastModel driven = fullorder::buildMast(p);
  ModalModel rom = extractModalModel(driven, lin);
  return {c, std::move(driven), std::move(rom)};
}

struct Comparison {
  double nrmse_rel, peak_rel_err, torque_err, force_err;
};

Comparison compare(const fullorder::DeploymentSeries& full,
                   const fullorder::DeploymentSeries& rom) {
  EXPECT_EQ(full.size(), rom.size());
  double num = 0, den = 0, peak_f = 0, peak_r = 0, tq = 0, tq_err = 0, ff = 0, ff_err = 0;
  for (std::size_t i = 0; i < full.size(); ++i) {
    EXPECT_NEAR(full.time_s[i], rom.time_s[i], 1e-12);
    const double a = full.end_relative_angular_acceleration_rad_s2[i];
    const double b = rom.end_relative_angular_acceleration_rad_s2[i];
    num += (a - b) * (a - b);
    den += a * a;
    peak_f = std::max(peak_f, std::abs(a));
    peak_r = std::max(peak_r, std::abs(b));
    tq = std::max(tq, std::abs(full.joint_torque_nm[i]));
    tq_err = std::max(tq_err, std::abs(full.joint_torque_nm[i] - rom.joint_torque_nm[i]));
    ff = std::max(ff, full.joint_force_n[i].norm());
    ff_err = std::max(ff_err, (full.joint_force_n[i] - rom.joint_force_n[i]).norm());
  }
  return {std::sqrt(num / den), std::abs(peak_f - peak_r) / peak_f, tq_err / tq, ff_err / ff};
}

TEST(RomVersusFullOrder, CoarseScheme1AgreesAndTheGapClosesWithTheFullOrderStep) {
  // Both models see the same linear physics here (θ̈ ≈ 580 rad/s², deflections ≪ wall thickness), so
  // their difference is the full order's time-discretisation error, second order in h (the ROM
  // steps each mode exactly). Measured: NRMSE of the relative end angular acceleration 7.9 % at
  // h = 25 µs and 2.0 % at 12.5 µs (≈ 24 and 48 steps per period of the 1.7 kHz bending pair);
  // torque and joint force max errors 2.1 % → 0.54 %, 2.2 % → 0.55 % of their peaks.
  const Scheme1Case c = buildScheme1(20);
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(c.config));
  Comparison cmp[2];
  const double steps[2] = {2.5e-5, 1.25e-5};
  for (int k = 0; k < 2; ++k) {
    fullorder::MastModel model =
        fullorder::buildMast(fullorder::mastParametersFromConfig(c.config));
    fullorder::DeploymentOptions o;
    o.integrator.time_step_s = steps[k];
    o.end_time_s = 0.05;
    const fullorder::DeploymentSeries full = fullorder::simulateDeployment(model, o);
    ModalDeploymentOptions ro;
    ro.end_time_s = 0.05;
    ro.step_s = steps[k];
    cmp[k] = compare(full, simulateModalDeployment(c.rom, drive, ro));
    std::printf(
        "[ measured ] h = %.3g s: NRMSE(rel) %.4f, peak rel %.4f, torque %.4f, force %.4f\n",
        steps[k], cmp[k].nrmse_rel, cmp[k].peak_rel_err, cmp[k].torque_err, cmp[k].force_err);
  }
  EXPECT_LT(cmp[1].nrmse_rel, 0.03);  // the target for a database sample (linearisation error alone)
  EXPECT_LT(cmp[1].peak_rel_err, 0.03);
  EXPECT_LT(cmp[1].torque_err, 0.01);
  EXPECT_LT(cmp[1].force_err, 0.01);
  // Second-order convergence of the full order towards the ROM: halving h divides the gap by ~4.
  EXPECT_GT(cmp[0].nrmse_rel / cmp[1].nrmse_rel, 3.0);
  EXPECT_GT(cmp[0].torque_err / cmp[1].torque_err, 3.0);
}

}  // namespace
}  // namespace mastrom::rom

namespace mastrom::rom {
namespace {

TEST(ModalDeployment, DriveJumpsBetweenSamplesActAtTheirTrueInstant) {
  // Breakpoints of the trapezoidal law at 17.3 ms, 82.7 ms and 100 ms fall between 1 ms samples.
  // Splitting the step there makes the coarse-step result equal to a 1 µs-step run sampled at the
  // same instants (the stepping is exact for piecewise-linear forcing), instead of smearing each
  // jump over a sample interval (a phase error of up to half a step).
  const ModalModel m = oneMode(2 * M_PI * 300.0, 0.01, 1.3);
  fullorder::DriveLawParameters dp;
  dp.duration_s = 0.1;
  dp.ramp_s = 0.0173;
  dp.total_angle_rad = 0.2;
  const fullorder::DriveLaw drive(dp);
  ModalDeploymentOptions coarse, fine;
  coarse.end_time_s = fine.end_time_s = 0.12;
  coarse.step_s = 1e-3;
  fine.step_s = 1e-6;
  const fullorder::DeploymentSeries a = simulateModalDeployment(m, drive, coarse);
  const fullorder::DeploymentSeries b = simulateModalDeployment(m, drive, fine);
  double peak = 0.0, diff = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::size_t j = i * 1000;
    ASSERT_NEAR(a.time_s[i], b.time_s[j], 1e-12);
    if (std::abs(a.time_s[i] - 0.1) < 1e-9) continue;  // θ̈ itself jumps at that sample
    peak = std::max(peak, std::abs(b.end_relative_angular_acceleration_rad_s2[j]));
    diff = std::max(diff, std::abs(a.end_relative_angular_acceleration_rad_s2[i] -
                                   b.end_relative_angular_acceleration_rad_s2[j]));
  }
  EXPECT_LT(diff, 1e-8 * peak);
}

}  // namespace
}  // namespace mastrom::rom

namespace mastrom::rom {
namespace {

/// max_i |a_i − b_i| / max_i |b_i| over a column of scalars or of vectors (norms).
double columnError(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    peak = std::max(peak, std::abs(b[i]));
  }
  return diff / peak;
}
double columnError(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  double diff = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    diff = std::max(diff, (a[i] - b[i]).norm());
    peak = std::max(peak, b[i].norm());
  }
  return diff / peak;
}

TEST(ModalDeployment, FastSteppingEqualsThePlainImplementation) {
  // Five random modes (50–500 Hz band, ζ ≈ 1 %), gravity off the Z axis with θ₀ = 0.3 rad, with and
  // without the Coriolis coupling; a trapezoidal law whose breakpoints fall between samples (split
  // steps), one whose breakpoints sit on the grid, and a cycloidal law.
  // Both codes evaluate the same exact maps and formulas, so they differ by
  //  * round-off: a few ε per step in a norm-preserving recursion, ≤ N·ε ≈ 1e-13 over N = 700;
  //  * the plain code's one-sided evaluations at t ± 1e-9 Δ where the fast one uses t itself for a
  //    continuous quantity: a relative forcing change of about 1e-9 Δ / t_r ≈ 1e-10 for Δ = 1 ms
  //    and the 17.3 ms ramp (θ̇² doubles the 6e-11 of θ̇).
  // Tolerance 1e-9 of each column's peak: ten times the larger of the two.
  ModalModel m = testing::randomBilinearModel(5, 11).value(0.4, 0.7);
  m.gravity_m_s2 = Eigen::Vector3d(0.5, -9.81, 0.2);
  m.reference_angle_rad = 0.3;
  const double tolerance = 1e-9;
  struct Law {
    DriveLawKind kind;
    double ramp_s;
  };
  for (const Law law : {Law{DriveLawKind::Trapezoidal, 0.0173},
                        Law{DriveLawKind::Trapezoidal, 0.02}, Law{DriveLawKind::Cycloidal, 0.02}}) {
    for (const bool coriolis : {false, true}) {
      fullorder::DriveLawParameters dp;
      dp.kind = law.kind;
      dp.duration_s = 0.5;
      dp.ramp_s = law.ramp_s;
      dp.total_angle_rad = 1.2;
      const fullorder::DriveLaw drive(dp);
      ModalDeploymentOptions o;
      o.end_time_s = 0.7;
      o.step_s = 1e-3;
      o.coriolis_coupling = coriolis;
      SCOPED_TRACE(toString(law.kind) + " ramp " + std::to_string(law.ramp_s) +
                   (coriolis ? " with Coriolis" : ""));
      const fullorder::DeploymentSeries fast = simulateModalDeployment(m, drive, o);
      const fullorder::DeploymentSeries plain = testing::referenceModalDeployment(m, drive, o);
      ASSERT_EQ(fast.size(), plain.size());
      EXPECT_NO_THROW(fast.checkConsistent());
      for (std::size_t i = 0; i < fast.size(); ++i) {
        ASSERT_EQ(fast.time_s[i], plain.time_s[i]);
        ASSERT_EQ(fast.drive_angle_rad[i], plain.drive_angle_rad[i]);
        ASSERT_EQ(fast.drive_acceleration_rad_s2[i], plain.drive_acceleration_rad_s2[i]);
      }
      EXPECT_LT(
          columnError(fast.end_angular_acceleration_rad_s2, plain.end_angular_acceleration_rad_s2),
          tolerance);
      EXPECT_LT(columnError(fast.end_relative_angular_acceleration_rad_s2,
                            plain.end_relative_angular_acceleration_rad_s2),
                tolerance);
      EXPECT_LT(columnError(fast.end_position_m, plain.end_position_m), tolerance);
      EXPECT_LT(columnError(fast.end_acceleration_m_s2, plain.end_acceleration_m_s2), tolerance);
      EXPECT_LT(columnError(fast.joint_force_n, plain.joint_force_n), tolerance);
      EXPECT_LT(columnError(fast.joint_torque_nm, plain.joint_torque_nm), tolerance);
      std::printf("[ measured ] %s ramp %.4g%s: rel. acc. %.2e, torque %.2e, force %.2e\n",
                  toString(law.kind).c_str(), law.ramp_s, coriolis ? " Coriolis" : "",
                  columnError(fast.end_relative_angular_acceleration_rad_s2,
                              plain.end_relative_angular_acceleration_rad_s2),
                  columnError(fast.joint_torque_nm, plain.joint_torque_nm),
                  columnError(fast.joint_force_n, plain.joint_force_n));

      // The streaming metrics against the plain series reduced by computeMetrics (same bound).
      const fullorder::DeploymentMetrics a = modalDeploymentMetrics(
          m, drive, o, 0.5, fullorder::kDefaultSettlingBandRadS2, PeakResolution::Samples);
      const fullorder::DeploymentMetrics b = fullorder::computeMetrics(plain, 0.5);
      EXPECT_NEAR(a.peak_rel_end_angular_acceleration, b.peak_rel_end_angular_acceleration,
                  tolerance * b.peak_rel_end_angular_acceleration);
      EXPECT_NEAR(a.rms_rel_end_angular_acceleration, b.rms_rel_end_angular_acceleration,
                  tolerance * b.rms_rel_end_angular_acceleration);
      EXPECT_NEAR(a.residual_rel_end_angular_acceleration, b.residual_rel_end_angular_acceleration,
                  tolerance * b.peak_rel_end_angular_acceleration);
      EXPECT_NEAR(a.peak_joint_force, b.peak_joint_force, tolerance * b.peak_joint_force);
      EXPECT_NEAR(a.peak_drive_torque, b.peak_drive_torque, tolerance * b.peak_drive_torque);
      EXPECT_NEAR(peakRelativeEndAcceleration(m, drive, o), b.peak_rel_end_angular_acceleration,
                  tolerance * b.peak_rel_end_angular_acceleration);
    }
  }
}

TEST(ModalDeployment, FreeDecayIntoTheSubnormalRangeIsFlushedAndTheCallersModeKept) {
  // One stiff, damped mode (1 kHz, ζ = 5 %: ζω ≈ 314 /s) rings after a short ramp, then decays
  // freely for 3 s: e^{−314·3} ≈ 1e-409, so without the flush its state would pass through the
  // subnormal range (below 2.2e-308, from t ≈ 2.3 s on). With it the tail is exactly zero and never
  // subnormal, and the caller's floating-point mode is unchanged after the call
  // (common/flush_denormals.hpp).
  ModalModel m = oneMode(2 * M_PI * 1000.0, 0.05, 1.7);
  m.damping_ratio = Eigen::VectorXd::Constant(1, 0.05);
  fullorder::DriveLawParameters dp;
  dp.duration_s = 0.02;
  dp.ramp_s = 0.01;
  dp.total_angle_rad = 1e-3;
  const fullorder::DriveLaw drive(dp);
  ModalDeploymentOptions o;
  o.end_time_s = 3.0;
  o.step_s = 1e-3;
  const fullorder::DeploymentSeries s = simulateModalDeployment(m, drive, o);
  const std::vector<double>& y = s.end_relative_angular_acceleration_rad_s2;
  double peak = 0.0;
  for (const double v : y) peak = std::max(peak, std::abs(v));
  EXPECT_GT(peak, 1e-3);
  for (std::size_t i = 0; i < y.size(); ++i) {
    ASSERT_NE(std::fpclassify(y[i]), FP_SUBNORMAL) << "sample " << i;
    ASSERT_TRUE(std::isfinite(y[i]));
  }
  EXPECT_EQ(y.back(), 0.0);  // 1e-409 of the peak: flushed
  volatile double tiny = DBL_MIN, half = 0.5;
  EXPECT_EQ(std::fpclassify(tiny * half), FP_SUBNORMAL) << "the caller's mode was not restored";
}

TEST(ModalDeployment, CoriolisCouplingNeedsTheCoriolisMatrix) {
  ModalModel m = oneMode(100.0, 0.05, 1.0);
  m.coriolis.resize(0, 0);
  const fullorder::DriveLaw drive(fullorder::DriveLawParameters{});
  ModalDeploymentOptions o;
  o.end_time_s = 0.01;
  o.step_s = 1e-3;
  EXPECT_NO_THROW(simulateModalDeployment(m, drive, o));
  o.coriolis_coupling = true;
  EXPECT_THROW(simulateModalDeployment(m, drive, o), InputError);
}

}  // namespace
}  // namespace mastrom::rom
