// Masts whose modules and interfaces differ (per-item configuration), a payload off the axis, a
// tabulated drive profile and the end point's tangential acceleration (docs/theory.md §1.4–§1.6,
// §2.6): a rigid mast against hand-computed rigid-body mechanics, per-item tables equal to the
// defaults against the plain configuration, and a table sampled from the cubic law against that law.
#include <cmath>
#include <cstdio>
#include <fstream>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "coarse_mast.hpp"
#include "fullorder/cubic_spline.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/drive_law.hpp"
#include "fullorder/mast_config.hpp"

namespace mastrom::fullorder {
namespace {

using testing::coarseScheme1;

/// Scheme 2 (3 modules) on the coarse ring: module 2 heavier, module 3 a camera head (heavier still,
/// its own inertia, centroid off the axis), interface 1 thicker than interface 2.
Config unequalMast() {
  Config c = coarseScheme1();
  c.mast.modules = 3;
  c.module_items[2].mass_kg = 0.8;
  ModuleItemConfig& head = c.module_items[3];
  head.mass_kg = 1.2;
  head.inertia_kg_m2 = std::array<double, 3>{2e-3, 3e-3, 3e-3};
  head.centroid_offset_m = std::array<double, 3>{0.01, 0.02, 0.005};
  c.interface_items[1].thickness_m = 0.003;
  validate(c);
  return c;
}

/// Hand computation of the stowed mast's mass, centroid (x, y) and moment of inertia about the
/// joint axis Z from its parts: module k a point mass at its centroid (x_k + c_x, c_y) plus its
/// own I_zz; interface k a thin-walled tube along X from x0 = x_k + d/2 to x0 + L
/// (m (R²/2 + x0² + x0 L + L²/3)). Cube centres x_k = (k − 1)(d + L): every side and length alike.
struct RigidMastData {
  double mass = 0, j_z = 0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
};

RigidMastData handComputed(const Config& c) {
  const double d = c.module.side_m, L = c.interface.length_m, R = c.interface.radius_m;
  RigidMastData r;
  Eigen::Vector2d first_moment = Eigen::Vector2d::Zero();
  for (int k = 1; k <= c.mast.modules; ++k) {
    const ModuleConfig m = c.moduleItem(k);
    const Eigen::Vector2d at((k - 1) * (d + L) + m.centroid_offset_m[0], m.centroid_offset_m[1]);
    r.j_z += m.principalInertia()[2] + m.mass_kg * at.squaredNorm();
    r.mass += m.mass_kg;
    first_moment += m.mass_kg * at;
  }
  for (int k = 1; k < c.mast.modules; ++k) {
    const double h = c.interfaceItem(k).thickness_m;
    const double m_shell = c.material.density_kg_m3 * h * 2 * M_PI * R * L;
    const double x0 = (k - 1) * (d + L) + d / 2;
    r.j_z += m_shell * (R * R / 2 + x0 * x0 + x0 * L + L * L / 3);
    r.mass += m_shell;
    first_moment += m_shell * Eigen::Vector2d(x0 + L / 2, 0.0);
  }
  r.centroid = first_moment / r.mass;
  return r;
}

TEST(RealMast, RigidUnequalModulesAndOffAxisPayloadFollowRigidBodyMechanics) {
  Config c = unequalMast();
  c.material.youngs_modulus_pa *= 1e6;  // rigid shells
  c.drive.law = DriveLawKind::Cubic;
  c.drive.angle_deg = 20.0;
  c.drive.duration_s = 0.1;
  MastModel model = buildMast(mastParametersFromConfig(c));
  const DeploymentOptions o = testing::rigidMastOptions(0.11);
  const DeploymentSeries s = simulateDeployment(model, o);

  const RigidMastData hand = handComputed(c);
  // The interpolated shell geometry differs from the tube by ~5e-4 in area (shell element tests).
  EXPECT_NEAR(model.totalMass(), hand.mass, 1e-3 * hand.mass);
  const std::vector<double> tangential = s.endTangentialAccelerations();
  const ModuleConfig head = c.moduleItem(3);
  const double end_radius =  // distance of the end module's centroid from the joint axis
      std::hypot(2 * (c.module.side_m + c.interface.length_m) + head.centroid_offset_m[0],
                 head.centroid_offset_m[1]);
  double peak_torque = 0, peak_force = 0, peak_tangential = 0;
  double err_torque = 0, err_force = 0, err_tangential = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double t = s.time_s[i];
    if (t <= 4.5 * o.integrator.time_step_s ||
        (t >= c.drive.duration_s - 1e-12 && t <= c.drive.duration_s + 4.5 * 2e-4))
      continue;
    const double th = s.drive_angle_rad[i], w = s.drive_rate_rad_s[i],
                 a = s.drive_acceleration_rad_s2[i];
    const Eigen::Vector3d rc(std::cos(th) * hand.centroid.x() - std::sin(th) * hand.centroid.y(),
                             std::sin(th) * hand.centroid.x() + std::cos(th) * hand.centroid.y(),
                             0.0);
    const Eigen::Vector3d ac = a * Eigen::Vector3d::UnitZ().cross(rc) - w * w * rc;
    peak_torque = std::max(peak_torque, std::abs(hand.j_z * a));
    peak_force = std::max(peak_force, hand.mass * ac.norm());
    peak_tangential = std::max(peak_tangential, std::abs(a * end_radius));
    err_torque = std::max(err_torque, std::abs(s.joint_torque_nm[i] - hand.j_z * a));
    err_force = std::max(err_force, (s.joint_force_n[i] - hand.mass * ac).norm());
    err_tangential = std::max(err_tangential, std::abs(tangential[i] - a * end_radius));
  }
  std::printf("[ measured ] unequal rigid mast, max error / peak: torque %.2e, joint force %.2e, "
              "tangential end acceleration %.2e\n",
              err_torque / peak_torque, err_force / peak_force, err_tangential / peak_tangential);
  EXPECT_LT(err_torque, 5e-3 * peak_torque);
  EXPECT_LT(err_force, 5e-3 * peak_force);
  EXPECT_LT(err_tangential, 5e-3 * peak_tangential);
}

/// A short fixed-step deployment of `c`.
DeploymentSeries shortDeployment(const Config& c, double end_time_s) {
  MastModel model = buildMast(mastParametersFromConfig(c));
  DeploymentOptions o;
  o.integrator.time_step_s = 2e-4;
  o.end_time_s = end_time_s;
  return simulateDeployment(model, o);
}

TEST(RealMast, ItemTablesEqualToTheDefaultsAreBitIdenticalToThePlainConfig) {
  Config plain = testing::turningScheme1();
  plain.mast.modules = 3;
  Config items = plain;
  for (int k = 1; k <= 3; ++k) {
    items.module_items[k].mass_kg = plain.module.mass_kg;
    items.module_items[k].side_m = plain.module.side_m;
    items.module_items[k].centroid_offset_m = std::array<double, 3>{0.0, 0.0, 0.0};
  }
  for (int k = 1; k <= 2; ++k) {
    items.interface_items[k].thickness_m = plain.interface.thickness_m;
    items.interface_items[k].length_m = plain.interface.length_m;
    items.interface_items[k].radius_m = plain.interface.radius_m;
  }
  validate(items);
  const DeploymentSeries a = shortDeployment(plain, 0.02);
  const DeploymentSeries b = shortDeployment(items, 0.02);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(a.joint_torque_nm == b.joint_torque_nm);
  EXPECT_TRUE(a.end_relative_angular_acceleration_rad_s2 ==
              b.end_relative_angular_acceleration_rad_s2);
  EXPECT_TRUE(a.end_acceleration_m_s2 == b.end_acceleration_m_s2);
  EXPECT_TRUE(a.joint_force_n == b.joint_force_n);
}

// ---------------------------------------------------------------------------------------------
// The tabulated drive law.

TEST(TableDrive, SplineThroughCubicLawSamplesIsTheCubicLaw) {
  DriveLawParameters cubic;
  cubic.kind = DriveLawKind::Cubic;
  cubic.total_angle_rad = 0.7;
  cubic.duration_s = 2.0;
  const DriveLaw exact(cubic);
  DriveLawParameters table;
  table.kind = DriveLawKind::Table;
  for (int i = 0; i <= 8; ++i) {
    const double t = 2.0 * i / 8;
    table.table_time_s.push_back(t);
    table.table_angle_rad.push_back(exact.at(t).angle_rad);
  }
  const DriveLaw law(table);
  EXPECT_EQ(law.parameters().duration_s, 2.0);
  EXPECT_EQ(law.breakpoints(), std::vector<double>{2.0});
  // A clamped cubic spline reproduces a cubic with the right end slopes exactly (round-off).
  for (double t = 0.0; t < 2.5; t += 0.0137) {
    const DriveState a = law.at(t), b = exact.at(t);
    EXPECT_NEAR(a.angle_rad, b.angle_rad, 1e-14) << t;
    EXPECT_NEAR(a.rate_rad_s, b.rate_rad_s, 1e-13) << t;
    EXPECT_NEAR(a.acceleration_rad_s2, b.acceleration_rad_s2, 1e-12) << t;
  }
}

TEST(TableDrive, SecondDerivativeIsContinuousAcrossRowsAndConvergesAsH2) {
  // Quintic samples: θ̈ of the spline is continuous at every row and its error falls ~4× per
  // halving of the row spacing (O(h²), de Boor ch. IV).
  DriveLawParameters quintic;
  quintic.kind = DriveLawKind::Quintic;
  quintic.duration_s = 1.0;
  const DriveLaw exact(quintic);
  double previous = 0;
  for (const int rows : {11, 21, 41}) {
    DriveLawParameters table;
    table.kind = DriveLawKind::Table;
    for (int i = 0; i < rows; ++i) {
      table.table_time_s.push_back(static_cast<double>(i) / (rows - 1));
      table.table_angle_rad.push_back(exact.at(table.table_time_s.back()).angle_rad);
    }
    const DriveLaw law(table);
    double err = 0;
    for (int i = 1; i + 1 < rows; ++i) {
      const double t = table.table_time_s[static_cast<std::size_t>(i)];
      EXPECT_NEAR(law.at(t - 1e-12).acceleration_rad_s2, law.at(t + 1e-12).acceleration_rad_s2,
                  1e-8)
          << "row " << i;
    }
    for (double t = 0.0; t < 1.0; t += 0.001)
      err = std::max(err, std::abs(law.at(t).acceleration_rad_s2 - exact.at(t).acceleration_rad_s2));
    if (previous > 0) {
      EXPECT_LT(err, 0.35 * previous) << rows << " rows";
    }
    previous = err;
  }
}

double nrmse(const std::vector<double>& a, const std::vector<double>& ref) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    num += (a[i] - ref[i]) * (a[i] - ref[i]);
    den += ref[i] * ref[i];
  }
  return std::sqrt(num / den);
}

TEST(TableDrive, TableSampledFromTheCubicLawReproducesItsFullOrderOutputs) {
  Config cubic = coarseScheme1();
  cubic.drive.law = DriveLawKind::Cubic;
  cubic.drive.angle_deg = 20.0;
  cubic.drive.duration_s = 0.1;
  const std::string csv = ::testing::TempDir() + "mastrom_test_real_mast_cubic.csv";
  {
    std::ofstream out(csv);
    out << "time_s, angle_deg\n";
    char line[96];
    for (int i = 0; i <= 20; ++i) {
      const double t = 0.1 * i / 20, tau = t / 0.1;
      std::snprintf(line, sizeof line, "%.17g, %.17g\n", t, 20.0 * tau * tau * (3 - 2 * tau));
      out << line;
    }
  }
  const Config table = applyConfigOverrides(cubic, {"drive.law=\"table\"", "drive.table=\"" + csv + "\""});
  EXPECT_EQ(table.drive.duration_s, 0.1);
  const DeploymentSeries a = shortDeployment(cubic, 0.12);
  const DeploymentSeries b = shortDeployment(table, 0.12);
  ASSERT_EQ(a.size(), b.size());
  const double e_rel = nrmse(b.end_relative_angular_acceleration_rad_s2,
                             a.end_relative_angular_acceleration_rad_s2);
  const double e_torque = nrmse(b.joint_torque_nm, a.joint_torque_nm);
  const double e_tangential = nrmse(b.endTangentialAccelerations(), a.endTangentialAccelerations());
  std::printf("[ measured ] table vs cubic law NRMSE: relative end angular acceleration %.2e, "
              "torque %.2e, tangential end acceleration %.2e\n",
              e_rel, e_torque, e_tangential);
  EXPECT_LT(e_rel, 5e-3);
  EXPECT_LT(e_torque, 5e-3);
  EXPECT_LT(e_tangential, 5e-3);
}

}  // namespace
}  // namespace mastrom::fullorder
