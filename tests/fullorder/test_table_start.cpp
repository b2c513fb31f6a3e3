// A tabulated drive starts at rest, whatever its length (docs/theory.md §1.5, §5.1): its clamped
// spline's rate at t = 0 is exactly the clamped 0, and a deployment under gravity starts from the
// static equilibrium at the start angle, carrying the mast's weight at the joint from the first
// instant. Before, the start was judged by an exact test on the initial velocities, and a table
// whose spline gave θ̇(0) = 10⁻¹⁹ rad/s (round-off) started undeformed, to drop under its weight.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "coarse_mast.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/drive_law.hpp"
#include "fullorder/mast_config.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The cycloidal law, Θ in T, sampled at `rows` equally spaced instants (a motor profile's table).
DriveLawParameters cycloidalTable(int rows, double angle_rad, double duration_s) {
  DriveLawParameters p;
  p.kind = DriveLawKind::Table;
  for (int i = 0; i < rows; ++i) {
    const double tau = static_cast<double>(i) / (rows - 1);
    p.table_time_s.push_back(duration_s * tau);
    p.table_angle_rad.push_back(angle_rad * (tau - std::sin(2 * kPi * tau) / (2 * kPi)));
  }
  return p;
}

TEST(TableStart, EveryTableFrom4To200RowsStartsExactlyAtRest) {
  // 45° in 0.5 s, the lengths that started wrong before among them (30, 40, 80 rows).
  for (int rows = 4; rows <= 200; ++rows) {
    const DriveLaw law(cycloidalTable(rows, kPi / 4, 0.5));
    EXPECT_EQ(law.at(0.0).rate_rad_s, 0.0) << rows << " rows";
    EXPECT_TRUE(law.startsAtRest()) << rows << " rows";
    // Just after the start the spline's own formula runs: its rate is small and positive.
    EXPECT_GE(law.at(1e-9).rate_rad_s, -law.restRateTolerance()) << rows << " rows";
  }
  // The tolerance means rest: for 45° in 0.5 s it is 64 ulps of the largest secant rate.
  const DriveLaw law(cycloidalTable(40, kPi / 4, 0.5));
  EXPECT_LT(law.restRateTolerance(), 1e-12);
  EXPECT_GT(law.restRateTolerance(), 0.0);
}

/// Scheme 2 on the coarse ring, gravity across the stowed mast (−Y, the mast along +X).
Config gravityMast() {
  Config c = testing::coarseScheme1();
  c.mast.modules = 3;
  c.simulation.gravity_m_s2 = {0.0, -9.81, 0.0};
  return c;
}

struct StartLoads {
  Eigen::Vector3d force;
  double torque = 0.0;
};

/// The joint force and drive torque at t = 0 of a fixed-step deployment of `model`.
StartLoads startLoads(MastModel& model) {
  DeploymentOptions o;
  o.integrator.time_step_s = 1e-4;
  o.end_time_s = 1e-4;
  const DeploymentSeries s = simulateDeployment(model, o);
  EXPECT_EQ(s.time_s.front(), 0.0);
  return {s.joint_force_n.front(), s.joint_torque_nm.front()};
}

/// Each table of `rows_list` (the cycloidal law, 45° in 0.5 s) starts a deployment under gravity
/// from the same static equilibrium as the cycloidal law itself.
void expectEquilibriumStarts(const std::vector<int>& rows_list) {
  // The reference: the cycloidal law itself, θ̈(0) = 0 (a table's spline has a small θ̈(0)).
  Config cubic = gravityMast();
  cubic.drive.law = DriveLawKind::Cycloidal;
  cubic.drive.angle_deg = 45.0;
  cubic.drive.duration_s = 0.5;
  MastModel reference = buildMast(mastParametersFromConfig(cubic));
  const StartLoads expected = startLoads(reference);
  // In equilibrium the joint carries the whole weight: the static solve's force tolerance (1e-9
  // of the largest force) bounds the difference.
  const double weight = reference.totalMass() * 9.81;
  EXPECT_NEAR(expected.force.y(), weight, 1e-8 * weight);
  EXPECT_NEAR(expected.force.x(), 0.0, 1e-8 * weight);
  // The weight's moment about the joint: the first moment of the undeformed mast (module centres
  // (k − 1)(d + L), the tubes' mid-points), within the ring's area error (~5e-4) and the sag.
  const double d = cubic.module.side_m, L = cubic.interface.length_m;
  const double m_module = cubic.module.mass_kg;
  const double m_shell = reference.totalMass() - 3 * m_module;
  const double moment = 9.81 * (m_module * (d + L) * (0 + 1 + 2) +
                                0.5 * m_shell * ((d / 2 + L / 2) + (d + L + d / 2 + L / 2)));
  EXPECT_NEAR(std::abs(expected.torque), moment, 1e-3 * moment);

  // Each table starts from the same static equilibrium (the drive enters it only through
  // θ(0) = 0); its spline's θ̈(0) adds at most the rigid turn's inertia, m_total ρ_end θ̈(0) to the
  // force and J θ̈(0) ≤ m_total ρ_end² θ̈(0) to the torque. Started undeformed, the force read
  // 5.03 N against 16.08 N on Scheme 2: a third of the weight.
  const double reach = 2 * (d + L) + d / 2;  // the farthest module face from the joint
  double worst_force = 0.0, worst_torque = 0.0;
  for (int rows : rows_list) {
    MastParameters p = mastParametersFromConfig(cubic);
    p.drive = cycloidalTable(rows, kPi / 4, 0.5);
    MastModel model = buildMast(p);
    const double start_acceleration = std::abs(model.baseJoint().driveAt(0.0).acceleration_rad_s2);
    const StartLoads got = startLoads(model);
    const double force_bound = reference.totalMass() * reach * start_acceleration + 1e-9 * weight;
    const double torque_bound =
        reference.totalMass() * reach * reach * start_acceleration + 1e-9 * moment;
    EXPECT_LE((got.force - expected.force).norm(), force_bound) << rows << " rows";
    EXPECT_LE(std::abs(got.torque - expected.torque), torque_bound) << rows << " rows";
    worst_force = std::max(worst_force, (got.force - expected.force).norm() / weight);
    worst_torque = std::max(worst_torque, std::abs(got.torque - expected.torque) / moment);
  }
  std::printf("[ measured ] %zu tables, largest difference from the cycloidal law's start: force "
              "%.2e of the weight, torque %.2e of its moment\n", rows_list.size(), worst_force,
              worst_torque);
}

TEST(TableStart, UnderGravityTheLengthsThatStartedWrongStartFromTheStaticEquilibrium) {
  // 30, 40 and 80 rows started undeformed before; 50 rows started right.
  expectEquilibriumStarts({30, 40, 50, 80});
}

TEST(TableStart, UnderGravityEveryTableFrom4To200RowsStartsFromTheStaticEquilibrium) {
  std::vector<int> rows_list;
  for (int rows = 4; rows <= 200; ++rows) rows_list.push_back(rows);
  expectEquilibriumStarts(rows_list);
}

}  // namespace
}  // namespace mastrom::fullorder
