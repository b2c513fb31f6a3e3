// Full-order deployment dynamics (docs/theory.md §5): a nearly rigid
// mast against rigid-body mechanics, energy conservation of free vibration, constraint residuals and
// time-step convergence. Short horizons and a coarse ring (1 × 6) keep each case to a few seconds;
// the physics does not depend on that choice (the rigid mast is rigid, the energy test is exact for
// any mesh).
#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "coarse_mast.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/static_solver.hpp"

namespace mastrom::fullorder {
namespace {

using testing::coarseScheme1;

/// Moment of inertia about the joint axis Z of the stowed mast, from its parts: modules (solid cubes,
/// I_zz + m x²) and thin-walled tubes along X from x0 to x0 + L (m (R²/2 + x0² + x0 L + L²/3)).
double rigidInertiaAboutZ(const MastParameters& p, double* total_mass, double* centroid_x) {
  const double d = p.module_side_m, L = p.interface_length_m, R = p.interface_radius_m;
  const double m_shell = p.density_kg_m3 * p.interface_thickness_m * 2 * M_PI * R * L;
  double j = 0, mass = 0, first_moment = 0;
  for (int k = 0; k < p.modules; ++k) {
    const double x = k * (d + L);
    j += p.module_mass_kg * d * d / 6 + p.module_mass_kg * x * x;
    mass += p.module_mass_kg;
    first_moment += p.module_mass_kg * x;
  }
  for (int k = 0; k + 1 < p.modules; ++k) {
    const double x0 = k * (d + L) + d / 2;
    j += m_shell * (R * R / 2 + x0 * x0 + x0 * L + L * L / 3);
    mass += m_shell;
    first_moment += m_shell * (x0 + L / 2);
  }
  *total_mass = mass;
  *centroid_x = first_moment / mass;
  return j;
}

class RigidMast : public ::testing::TestWithParam<DriveLawKind> {};

TEST_P(RigidMast, TorqueForceAndEndAccelerationFollowRigidBodyMechanics) {
  Config c = coarseScheme1();
  c.material.youngs_modulus_pa *= 1e6;  // "10⁶ times stiffer" shells: a nearly rigid mast
  c.drive.law = GetParam();
  c.drive.angle_deg = 20.0;
  c.drive.duration_s = 0.1;
  c.drive.ramp_s = 0.02;
  MastParameters p = mastParametersFromConfig(c);
  MastModel model = buildMast(p);
  const DeploymentOptions o = testing::rigidMastOptions(0.11);
  const DeploymentSeries s = simulateDeployment(model, o);

  double mass = 0, xc = 0;
  const double j = rigidInertiaAboutZ(p, &mass, &xc);
  // The interpolated shell geometry differs from the tube by ~5e-4 in area (shell element tests).
  EXPECT_NEAR(model.totalMass(), mass, 1e-3 * mass);
  double peak_acc = 0, peak_torque = 0, peak_force = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    peak_acc = std::max(peak_acc, std::abs(s.drive_acceleration_rad_s2[i]));
    peak_torque = std::max(peak_torque, std::abs(j * s.drive_acceleration_rad_s2[i]));
  }
  std::vector<double> jumps{0.0, c.drive.duration_s};  // θ̈ or θ⃛ discontinuities
  if (GetParam() == DriveLawKind::Trapezoidal) {
    jumps.push_back(c.drive.ramp_s);
    jumps.push_back(c.drive.duration_s - c.drive.ramp_s);
  }
  auto nearJump = [&](double t) {
    for (double tj : jumps)
      if (t >= tj - 1e-12 && t <= tj + 4.5 * o.integrator.time_step_s) return true;
    return false;
  };
  double max_torque_err = 0, max_force_err = 0, max_acc_err = 0;
  int compared = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_LE(s.constraint_residual[i], 1e-9) << "t = " << s.time_s[i];
    if (nearJump(s.time_s[i])) continue;
    ++compared;
    const double th = s.drive_angle_rad[i], w = s.drive_rate_rad_s[i],
                 a = s.drive_acceleration_rad_s2[i];
    const Eigen::Vector3d rc = xc * Eigen::Vector3d(std::cos(th), std::sin(th), 0);
    const Eigen::Vector3d ac = a * Eigen::Vector3d::UnitZ().cross(rc) - w * w * rc;
    peak_force = std::max(peak_force, mass * ac.norm());
    max_torque_err = std::max(max_torque_err, std::abs(s.joint_torque_nm[i] - j * a));
    max_force_err = std::max(max_force_err, (s.joint_force_n[i] - mass * ac).norm());
    max_acc_err = std::max(max_acc_err, std::abs(s.end_angular_acceleration_rad_s2[i].z() - a));
  }
  EXPECT_GE(compared, static_cast<int>(s.size() - 5 * jumps.size()));
  std::printf("[ measured ] %s: max error / peak: torque %.2e, joint force %.2e, end angular "
              "acceleration %.2e\n", toString(GetParam()).c_str(), max_torque_err / peak_torque,
              max_force_err / peak_force, max_acc_err / peak_acc);
  EXPECT_LT(max_torque_err, 5e-3 * peak_torque);
  EXPECT_LT(max_force_err, 5e-3 * peak_force);
  EXPECT_LT(max_acc_err, 5e-3 * peak_acc);
}

INSTANTIATE_TEST_SUITE_P(AllDriveLaws, RigidMast,
                         ::testing::Values(DriveLawKind::Trapezoidal, DriveLawKind::Cubic,
                                           DriveLawKind::Quintic, DriveLawKind::Cycloidal),
                         [](const auto& info) { return toString(info.param); });

/// Free vibration of a locked, undamped mast released from a static deflection (gravity preload
/// removed at t = 0): kinetic + strain energy is conserved by ρ∞ = 1 and dissipated by ρ∞ < 1.
double freeVibrationEnergyChange(double rho_inf, int steps) {
  Config c = coarseScheme1();
  c.material.damping_s = 0.0;
  MastParameters p = mastParametersFromConfig(c);
  p.lock_angle_rad = 0.0;
  MastParameters loaded = p;
  loaded.gravity_m_s2 = Eigen::Vector3d(0, -2000.0, 0);  // strong lateral load: a visible deflection
  const MastModel preload = buildMast(loaded);
  const StaticResult eq =
      solveStatic(preload.system(), preload.system().referenceCoordinates(), StaticSolverOptions{});
  MastModel model = buildMast(p);
  MultibodySystem& sys = model.system();
  GeneralizedAlphaOptions o;
  o.rho_inf = rho_inf;
  o.time_step_s = 2e-5;  // ~30 steps per period of the first bending mode (1.7 kHz)
  GeneralizedAlpha ga(sys, o);
  ga.initialize(eq.q, Eigen::VectorXd::Zero(sys.dofCount()), 0.0);
  const double e0 = sys.strainEnergy(ga.state().q);
  EXPECT_GT(e0, 0.0);
  for (int i = 0; i < steps; ++i) {
    const StepReport r = ga.step();
    EXPECT_LE(r.constraint_residual, 1e-9);
  }
  const double e1 = sys.strainEnergy(ga.state().q) + sys.kineticEnergy(ga.state().qdot);
  return (e1 - e0) / e0;
}

TEST(FreeVibration, EnergyIsConservedWithRhoInfOne) {
  const double change = freeVibrationEnergyChange(1.0, 2000);
  std::printf("[ measured ] rho_inf = 1: relative energy change over 2000 steps %.2e\n", change);
  EXPECT_LT(std::abs(change), 1e-3);
}

TEST(FreeVibration, EnergyDecaysWithRhoInfBelowOne) {
  const double change = freeVibrationEnergyChange(0.6, 2000);
  std::printf("[ measured ] rho_inf = 0.6: relative energy change over 2000 steps %.2e\n", change);
  EXPECT_LT(change, -1e-3);
}

/// With gravity the deployment starts from the static equilibrium at the start angle (theory
/// §5.1): the first milliseconds of a smooth (cycloidal, θ̈(0) = 0) swing then show the same
/// relative end angular acceleration as without gravity, up to the slow change of the gravity
/// load as the mast turns; started undeformed, the mast drops and rings under its weight.
TEST(GravityStart, DeploymentStartsFromTheStaticEquilibrium) {
  Config c = coarseScheme1();
  c.drive.law = DriveLawKind::Cycloidal;
  c.drive.angle_deg = 10.0;
  c.drive.duration_s = 0.04;
  const auto run = [&](const Eigen::Vector3d& g, bool equilibrium) {
    MastParameters p = mastParametersFromConfig(c);
    p.gravity_m_s2 = g;
    MastModel model = buildMast(p);
    DeploymentOptions o;
    o.integrator.time_step_s = 2.5e-5;
    o.end_time_s = 0.01;
    o.start_in_equilibrium = equilibrium;
    return simulateDeployment(model, o).end_relative_angular_acceleration_rad_s2;
  };
  const Eigen::Vector3d gravity(0.0, -9.81, 0.0), none = Eigen::Vector3d::Zero();
  const std::vector<double> r0 = run(none, true), rg = run(gravity, true), rd = run(gravity, false);
  ASSERT_EQ(r0.size(), rg.size());
  ASSERT_EQ(r0.size(), rd.size());
  double peak = 0.0, diff_equilibrium = 0.0, diff_undeformed = 0.0;
  for (std::size_t i = 0; i < r0.size(); ++i) {
    peak = std::max(peak, std::abs(r0[i]));
    diff_equilibrium = std::max(diff_equilibrium, std::abs(rg[i] - r0[i]));
    diff_undeformed = std::max(diff_undeformed, std::abs(rd[i] - r0[i]));
  }
  std::printf("[ measured ] first 10 ms, peak |r| %.4g rad/s^2 without gravity; with gravity "
              "started in equilibrium it moves by %.3g, started undeformed by %.3g rad/s^2\n",
              peak, diff_equilibrium, diff_undeformed);
  EXPECT_GT(peak, 0.0);
  EXPECT_LT(diff_equilibrium, 0.01 * peak);
  EXPECT_GT(diff_undeformed, 10.0 * diff_equilibrium);
}

TEST(DeploymentConvergence, HalvingTheTimeStepChangesPeakRelativeAccelerationLittle) {
  // Scheme 1, trapezoidal drive compressed to 40 ms so the horizon is short; the relative end
  // angular acceleration is a ~1.7 kHz response to the θ̈ jumps, resolved with 12 and 24 steps per
  // period at the two steps.
  Config c = coarseScheme1();
  c.drive.angle_deg = 10.0;
  c.drive.duration_s = 0.04;
  c.drive.ramp_s = 0.01;
  double peaks[2];
  for (int k = 0; k < 2; ++k) {
    MastModel model = buildMast(mastParametersFromConfig(c));
    DeploymentOptions o;
    o.integrator.time_step_s = k == 0 ? 5e-5 : 2.5e-5;
    o.end_time_s = 0.045;
    const DeploymentSeries s = simulateDeployment(model, o);
    peaks[k] = computeMetrics(s, c.drive.duration_s).peak_rel_end_angular_acceleration;
    for (double r : s.constraint_residual) ASSERT_LE(r, 1e-9);
  }
  EXPECT_GT(peaks[0], 0.0);
  std::printf("[ measured ] peak relative end angular acceleration: %.6g (50 us), %.6g (25 us) "
              "rad/s^2, change %.3f %%\n", peaks[0], peaks[1],
              100.0 * std::abs(peaks[0] - peaks[1]) / peaks[1]);
  EXPECT_LT(std::abs(peaks[0] - peaks[1]), 0.02 * peaks[1])
      << "peaks " << peaks[0] << " and " << peaks[1] << " rad/s^2";
}

}  // namespace
}  // namespace mastrom::fullorder

namespace mastrom::fullorder {
namespace {

TEST(EliminatedSystem, RemovesSixEquationsPerRingNodeAndGivesTheSameDeployment) {
  Config c = coarseScheme1();
  c.drive.angle_deg = 10.0;
  c.drive.duration_s = 0.04;
  c.drive.ramp_s = 0.01;
  MastModel model = buildMast(mastParametersFromConfig(c));
  const EliminatedSystem reduced(model.system());
  // Scheme 1, 1 × 6 ring: two bonded rings of 6 nodes, 6 linear equations (r and r_y) each.
  EXPECT_EQ(reduced.eliminatedCount(), 2 * 6 * 6);
  EXPECT_EQ(reduced.constraintCount(), model.constraintCount() - 2 * 6 * 6);
  // The reference configuration satisfies the eliminated equations: restrict ∘ expand = identity.
  const Eigen::VectorXd q0 = model.system().referenceCoordinates();
  EXPECT_LT((reduced.expandPositions(reduced.restrict(q0)) - q0).cwiseAbs().maxCoeff(), 1e-15);

  DeploymentOptions o;
  o.integrator.time_step_s = 5e-5;
  o.end_time_s = 0.045;
  o.eliminate_linear_constraints = true;
  const DeploymentSeries a = simulateDeployment(model, o);
  o.eliminate_linear_constraints = false;
  const DeploymentSeries b = simulateDeployment(model, o);
  ASSERT_EQ(a.size(), b.size());
  double peak_rel = 0, peak_tau = 0, d_rel = 0, d_tau = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    peak_rel = std::max(peak_rel, std::abs(b.end_relative_angular_acceleration_rad_s2[i]));
    peak_tau = std::max(peak_tau, std::abs(b.joint_torque_nm[i]));
    d_rel = std::max(d_rel, std::abs(a.end_relative_angular_acceleration_rad_s2[i] -
                                     b.end_relative_angular_acceleration_rad_s2[i]));
    d_tau = std::max(d_tau, std::abs(a.joint_torque_nm[i] - b.joint_torque_nm[i]));
  }
  // Same discrete problem; the two Newton paths differ only within the force tolerance (1e-6).
  std::printf("[ measured ] eliminated vs multipliers: max diff / peak: rel. acceleration %.2e, "
              "torque %.2e\n", d_rel / peak_rel, d_tau / peak_tau);
  EXPECT_LT(d_rel, 1e-4 * peak_rel);
  EXPECT_LT(d_tau, 1e-4 * peak_tau);
}

}  // namespace
}  // namespace mastrom::fullorder
