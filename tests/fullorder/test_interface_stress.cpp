// Interface stresses over a deployment (fullorder/interface_stress.hpp, docs/theory.md §6.3):
// the section moment at the base of interface 1 against the rigid-body moment of the inertial
// forces of everything beyond it, zero stress in a rigid motion, the bookkeeping of peaks,
// histories and margins.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <Eigen/Geometry>

#include "coarse_mast.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/interface_stress.hpp"
#include "fullorder/interface_stress_io.hpp"
#include "fullorder/mast_config.hpp"

namespace mastrom::fullorder {
namespace {

using testing::coarseScheme1;

/// Σ over the parts beyond the base edge of interface 1 of ∫ x(x − c) + y² dm (the stowed mast
/// along X, pivot at the origin, c = d/2 the ring centre): the moment about c of the inertial
/// forces of a rigid rotation with angular acceleration θ̈ is −θ̈ times this (centripetal forces
/// point at the pivot, along the axis, and have no moment about c). Modules: solid cubes,
/// I_zz = m d²/6; shells: thin tubes from x0 to x0 + L, ∫y² dm = m R²/2.
double inertiaBeyondBaseOfInterface1(const MastParameters& p) {
  const double d = p.module_side_m, L = p.interface_length_m, R = p.interface_radius_m;
  const double c = d / 2;
  const double m_shell = p.density_kg_m3 * p.interface_thickness_m * 2 * M_PI * R * L;
  double j = 0.0;
  for (int k = 1; k < p.modules; ++k) {
    const double x = k * (d + L);
    j += p.module_mass_kg * (d * d / 6 + x * (x - c));
  }
  for (int k = 0; k + 1 < p.modules; ++k) {
    const double x0 = k * (d + L) + d / 2;
    j += m_shell * (R * R / 2 + x0 * x0 + x0 * L + L * L / 3 - c * (x0 + L / 2));
  }
  return j;
}

/// Scheme 2 (3 modules) on a 1 × 6 ring, trapezoidal drive with a 0.2 s ramp: θ̈ is constant over
/// the ramp. Kelvin–Voigt damping μ = 2e-4 s (ζ ≈ μω/2 ≈ 0.2 for the ~300 Hz bending of the mast)
/// lets the ringing that the jump of θ̈ at t = 0 starts die out within the first half of the ramp,
/// so the mean over the second half is the quasi-static moment; the damping forces are internal
/// and do not change it.
TEST(InterfaceStress, BaseMomentEqualsInertialMomentOfTheMastBeyond) {
  Config c = coarseScheme1();
  c.mast.modules = 3;
  c.material.damping_s = 2e-4;
  c.drive.ramp_s = 0.2;
  const MastParameters p = mastParametersFromConfig(c);
  MastModel model = buildMast(p);
  DeploymentOptions o;
  o.integrator.time_step_s = 1e-4;
  o.end_time_s = 0.2;
  InterfaceStressMonitor monitor(model);
  o.state_observer = observeInterfaceStresses(monitor);
  const DeploymentSeries s = simulateDeployment(model, o);
  const InterfaceStressResult& r = monitor.result();
  ASSERT_EQ(r.time_s.size(), s.size());
  double mean = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < r.time_s.size(); ++i) {
    if (r.time_s[i] < 0.1 || r.time_s[i] >= 0.2 - 1e-9) continue;
    mean += r.history[0].base_moment_nm[i].z();
    ++count;
  }
  mean /= count;
  const double theta_ddot = s.drive_acceleration_rad_s2[s.size() / 2];
  const double expected = -theta_ddot * inertiaBeyondBaseOfInterface1(p);
  std::printf("[ measured ] base bending moment of interface 1: %.6g N m, rigid-body %.6g N m, "
              "error %.2e\n", mean, expected, std::abs(mean - expected) / std::abs(expected));
  EXPECT_NEAR(mean, expected, 0.01 * std::abs(expected));
  // The tip edge carries the same less the shell's own inertia: smaller in magnitude.
  EXPECT_LT(std::abs(r.history[0].tip_moment_nm[s.size() / 2].z()), std::abs(mean));

  // Module 1's centroid is pinned, so the joint's force on it (from the base joint's multipliers)
  // balances the section force of interface 1's base edge: F_joint = −R(θ) F_base at every
  // instant — the method of sections agrees with the constraint multipliers.
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double th = s.drive_angle_rad[i];
    Eigen::Matrix3d axes;
    axes << std::cos(th), -std::sin(th), 0, std::sin(th), std::cos(th), 0, 0, 0, 1;
    const Eigen::Vector3d section = axes * r.history[0].base_force_n[i];
    worst = std::max(worst, (s.joint_force_n[i] + section).norm());
    scale = std::max(scale, s.joint_force_n[i].norm());
  }
  std::printf("[ measured ] joint force against the section force of interface 1's base: max "
              "difference %.2e of the peak %.4g N\n", worst / scale, scale);
  EXPECT_LT(worst, 1e-6 * scale);
}

TEST(InterfaceStress, RigidRotationGivesNoStress) {
  MastModel model = buildMast(mastParametersFromConfig(coarseScheme1()));
  InterfaceStressMonitor monitor(model);
  const Eigen::VectorXd turned = model.rotatedReference(0.7);
  Eigen::VectorXd spin(turned.size());
  for (Eigen::Index k = 0; k < turned.size() / 3; ++k)
    spin.segment<3>(3 * k) = Eigen::Vector3d(0, 0, 1.3).cross(Eigen::Vector3d(turned.segment<3>(3 * k)));
  monitor.evaluate(0.0, turned, spin, Eigen::VectorXd::Zero(turned.size()));
  const InterfaceStressResult& r = monitor.result();
  ASSERT_EQ(r.history.size(), 1u);
  EXPECT_LT(r.history[0].max_von_mises_pa[0], 1e-3);  // Pa: round-off of E·ε is ~1e-5 Pa
  EXPECT_LT(r.history[0].base_force_n[0].norm(), 1e-12);
}

TEST(InterfaceStress, AdaptiveRunResamplesOntoTheOutputGridAndKeepsThePeak) {
  Config c = testing::turningScheme1();  // 10° in 0.5 s, 20 ms ramps
  c.simulation.adaptive = true;
  c.simulation.end_time_s = 0.03;
  c.output.step_s = 1e-3;
  MastModel model = buildMast(mastParametersFromConfig(c));
  DeploymentOptions o = deploymentFromConfig(c);
  InterfaceStressMonitor monitor = stressMonitorFor(model, o);
  monitor.requestFields({0.0151, 0.005});
  o.state_observer = observeInterfaceStresses(monitor);
  DeploymentStatistics stats;
  const DeploymentSeries s = simulateDeployment(model, o, &stats);
  // At most one evaluation per output interval, plus the piece starts and the end.
  EXPECT_LE(monitor.result().time_s.size(), s.size() + 3);
  EXPECT_LT(monitor.result().time_s.size(), static_cast<std::size_t>(stats.steps));
  const InterfaceStressResult r = monitor.resample(s.time_s);
  ASSERT_EQ(r.time_s.size(), s.size());
  ASSERT_EQ(r.history[0].max_von_mises_pa.size(), s.size());
  const InterfaceStressPeak& peak = r.peak[0];
  EXPECT_GT(peak.von_mises_pa, 0.0);
  double largest = 0.0;
  for (double v : monitor.result().history[0].max_von_mises_pa) largest = std::max(largest, v);
  EXPECT_EQ(peak.von_mises_pa, largest);
  EXPECT_EQ(peak.field_von_mises_pa.size(), 6u * 9u * 3u);
  EXPECT_EQ(*std::max_element(peak.field_von_mises_pa.begin(), peak.field_von_mises_pa.end()),
            peak.von_mises_pa);
  // Fields at the requested instants: at the first evaluation at or after each (in time order).
  ASSERT_EQ(r.snapshots.size(), 2u);
  EXPECT_EQ(r.snapshots[0].requested_time_s, 0.005);
  EXPECT_GE(r.snapshots[0].time_s, 0.005);
  EXPECT_LT(r.snapshots[1].time_s, 0.0151 + o.output_step_s);
  EXPECT_EQ(r.snapshots[1].field_von_mises_pa[0].size(), peak.field_von_mises_pa.size());
  // The peak sits at a bonded edge (x = 0 or L) for a mast swung about its base.
  EXPECT_TRUE(peak.axial_position_m < 1e-9 || peak.axial_position_m > 0.05 - 1e-9)
      << peak.axial_position_m;

  // The file layout and its ParaView companion.
  const std::string dir = MASTROM_BINARY_DIR "/tests";
  const std::string path = dir + "/interface_stress_layout.h5";
  {
    h5::AtomicH5Writer writer(path);
    writer.file().createGroup("/metrics");
    writeInterfaceStresses(writer.file(), r, s.size(), 2.7e8);
    writer.commit();
  }
  const h5::File file = h5::File::open(path, h5::OpenMode::ReadOnly);
  EXPECT_EQ(file.readDoubles("/interfaces/1/max_von_mises"), r.history[0].max_von_mises_pa);
  EXPECT_EQ(file.readUnits("/interfaces/1/max_von_mises"), "Pa");
  EXPECT_EQ(file.readUnits("/interfaces/1/base/moment"), "N*m");
  EXPECT_EQ(file.datasetShape("/interfaces/1/peak/von_mises_field"),
            (std::vector<std::size_t>{6 * 9, 3}));
  EXPECT_EQ(file.readDoubleAttribute("/metrics", "peak_von_mises_interface_1"), peak.von_mises_pa);
  EXPECT_DOUBLE_EQ(file.readDoubleAttribute("/metrics", "min_margin_of_safety"),
                   2.7e8 / peak.von_mises_pa - 1.0);
  const std::string xdmf = dir + "/interface_stress_layout.xdmf";
  writeInterfaceStressXdmf(xdmf, "interface_stress_layout.h5", r);
  std::stringstream text;
  text << std::ifstream(xdmf).rdbuf();
  EXPECT_NE(text.str().find("NumberOfElements=\"24\""), std::string::npos);  // 6 elements × 4
  EXPECT_NE(text.str().find("interface_stress_layout.h5:/interfaces/1/peak/von_mises_walls"),
            std::string::npos);
  EXPECT_NE(text.str().find("interface_stress_layout.h5:/interfaces/1/fields/2/von_mises_walls"),
            std::string::npos);
  EXPECT_EQ(file.readDoubles("/interfaces/1/fields/2/von_mises_walls").size(), 6u * 9u);
  // A history that does not match /time is refused.
  h5::AtomicH5Writer refused(dir + "/interface_stress_refused.h5");
  EXPECT_THROW(writeInterfaceStresses(refused.file(), r, s.size() + 1, std::nullopt),
               UsageError);
}

/// The model-level linearised stresses (per unit of a direction, as a modal ROM stores per mode)
/// against central differences of the nonlinear ones about the turned reference.
TEST(InterfaceStress, LinearizedPointStressesMatchCentralDifferences) {
  MastModel model = buildMast(mastParametersFromConfig(coarseScheme1()));
  const InterfaceStressMonitor monitor(model);
  const Eigen::VectorXd q = model.rotatedReference(0.4);
  const Eigen::VectorXd d = Eigen::VectorXd::Random(q.size()) * 1e-3;
  const double step = std::cbrt(std::numeric_limits<double>::epsilon());
  const Eigen::VectorXd qp = q + step * d, qm = q - step * d;
  const std::vector<ShellPointStress> lin = monitor.linearizedPointStresses(0, q, d);
  const std::vector<ShellPointStress> sp = monitor.pointStresses(0, qp, nullptr);
  const std::vector<ShellPointStress> sm = monitor.pointStresses(0, qm, nullptr);
  ASSERT_EQ(lin.size(), 6u * 9u);
  double scale = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < lin.size(); ++i) {
    for (int z = 0; z < kShellSurfaces; ++z) {
      scale = std::max(scale, lin[i].stress_pa[z].norm());
      worst = std::max(worst, ((sp[i].stress_pa[z] - sm[i].stress_pa[z]) / (2 * step) -
                               lin[i].stress_pa[z]).norm());
    }
  }
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(worst, 1e-6 * scale);  // truncation and round-off ~1e-10 relative (∛ε step)
}

TEST(InterfaceStress, MarginOfSafety) {
  InterfaceStressResult r;
  r.peak.resize(2);
  r.peak[0].von_mises_pa = 100e6;
  r.peak[1].von_mises_pa = 200e6;
  const InterfaceStressMetrics m = interfaceStressMetrics(r, 300e6);
  ASSERT_EQ(m.margin_of_safety.size(), 2u);
  EXPECT_DOUBLE_EQ(m.margin_of_safety[0], 2.0);
  EXPECT_DOUBLE_EQ(m.margin_of_safety[1], 0.5);
  EXPECT_DOUBLE_EQ(*m.min_margin_of_safety, 0.5);
  const InterfaceStressMetrics none = interfaceStressMetrics(r, std::nullopt);
  EXPECT_TRUE(none.margin_of_safety.empty());
  EXPECT_FALSE(none.min_margin_of_safety.has_value());
}

}  // namespace
}  // namespace mastrom::fullorder
