// The mass of a mast and of its items (fullorder/mast_mass.hpp, docs/theory.md §1.7): against a
// hand calculation, and against the full order's assembled mass matrix (its total translational
// mass uᵀMu, u a uniform unit translation, whole and restricted to each item's coordinates).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fullorder/mast_mass.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Scheme 3 whose items differ: module 4 carries a camera head, interface 2 is longer, thicker and
/// wider, and the ring has 12 elements (the mesh must not change the mass).
MastParameters differingItems() {
  MastParameters p;
  p.modules = 4;
  p.density_kg_m3 = 1200.0;
  p.elements_circumferential = 12;
  ModuleProperties head;
  head.side_m = 0.12;
  head.mass_kg = 1.75;
  p.module_items[3] = head;
  InterfaceProperties wide;
  wide.length_m = 0.08;
  wide.radius_m = 0.05;
  wide.thickness_m = 0.003;
  wide.elements_axial = 3;
  wide.elements_circumferential = 16;
  p.interface_items[1] = wide;
  return p;
}

/// uᵀ M u over the coordinates [first, first + count) of the assembled mass matrix: the
/// translational mass the model holds there.
double translationalMass(const MastModel& mast, int first, int count) {
  const Eigen::VectorXd u = mast.system().uniformField(Eigen::Vector3d::UnitY());
  Eigen::VectorXd part = Eigen::VectorXd::Zero(u.size());
  part.segment(first, count) = u.segment(first, count);
  return part.dot(mast.system().massMatrix() * part);
}

TEST(MastMass, ShellEqualsTheHandCalculation) {
  // π (r_o² − r_i²) L ρ with r_o = 42 mm, r_i = 40 mm: the default interface, by hand.
  const double hand = kPi * (0.042 * 0.042 - 0.040 * 0.040) * 0.05 * 2700.0;
  EXPECT_NEAR(shellMassKg(0.041, 0.002, 0.05, 2700.0), hand, 1e-15 * hand);
  // 2π R h L ρ, the same volume.
  EXPECT_NEAR(shellMassKg(0.041, 0.002, 0.05, 2700.0), 2 * kPi * 0.041 * 0.002 * 0.05 * 2700.0,
              1e-15 * hand);
}

TEST(MastMass, ItemsAndTotalEqualTheHandCalculation) {
  const MastParameters p = differingItems();
  const MastMass m = mastMass(p);
  ASSERT_EQ(m.module_kg.size(), 4u);
  ASSERT_EQ(m.interface_kg.size(), 3u);
  EXPECT_EQ(m.module_kg[0], 0.5);
  EXPECT_EQ(m.module_kg[3], 1.75);
  const double narrow = kPi * (0.042 * 0.042 - 0.040 * 0.040) * 0.05 * 1200.0;
  const double wide = kPi * (0.0515 * 0.0515 - 0.0485 * 0.0485) * 0.08 * 1200.0;
  EXPECT_NEAR(m.interface_kg[0], narrow, 1e-14 * narrow);
  EXPECT_NEAR(m.interface_kg[1], wide, 1e-14 * wide);
  EXPECT_NEAR(m.interface_kg[2], narrow, 1e-14 * narrow);
  const double total = 3 * 0.5 + 1.75 + 2 * narrow + wide;
  EXPECT_NEAR(m.total_kg, total, 1e-14 * total);
}

TEST(MastMass, ModulesEqualTheAssembledMassMatrix) {
  // A module's 12 × 12 block holds its configured mass exactly (docs/theory.md §2.1: M_r is built
  // from m, the centroid and the inertia), and the whole matrix is the sum of its items'.
  const MastParameters p = differingItems();
  const MastModel mast = buildMast(p);
  const MastMass m = mastMass(p);
  double items = 0.0;
  for (int k = 0; k < mast.moduleCount(); ++k) {
    const double block = translationalMass(mast, mast.moduleDofOffset(k), 12);
    EXPECT_NEAR(block, m.module_kg[k], 1e-14 * m.module_kg[k]) << "module " << k + 1;
    items += block;
  }
  for (int k = 0; k < mast.interfaceCount(); ++k) {
    const MastModel::InterfaceRange& r = mast.interfaceRange(k);
    items += translationalMass(mast, r.first_dof, r.dof_count);
  }
  EXPECT_NEAR(mast.system().totalMass(), items, 1e-13 * items);
  EXPECT_NEAR(translationalMass(mast, 0, mast.dofCount()), items, 1e-13 * items);
}

TEST(MastMass, ShellsOfTheAssembledMassMatrixConvergeToTheHandCalculation) {
  // The element mass ρh∫SᵀS dA is integrated over the interpolated reference surface
  // (dA = |g_x × g_y|, docs/theory.md §2.2): the ring of N_circ cubic Hermite arcs is not the
  // circle, so the model's shell mass differs from (1.12) by the geometric discretisation of the
  // ring, which falls like N_circ⁻⁴ (the Hermite interpolant of a smooth curve). Measured: the
  // difference and its rate, on meshes of 8, 16 and 32 elements per ring.
  double previous = 0.0;
  for (const int n : {8, 16, 32}) {
    MastParameters p;
    p.modules = 2;
    p.elements_circumferential = n;
    const MastModel mast = buildMast(p);
    const MastModel::InterfaceRange& r = mast.interfaceRange(0);
    const double model = translationalMass(mast, r.first_dof, r.dof_count);
    const double hand = kPi * (0.042 * 0.042 - 0.040 * 0.040) * 0.05 * 2700.0;
    const double relative = std::abs(model - hand) / hand;
    std::printf(
        "[ measured ] %2d elements per ring: shell mass %.12g kg, (1.12) %.12g kg, "
        "relative difference %.3e\n",
        n, model, hand, relative);
    if (previous > 0.0) {
      // Fourth order: each halving of the element divides the difference by 2⁴ = 16.
      EXPECT_GT(previous / relative, 12.0) << n;
      EXPECT_LT(previous / relative, 20.0) << n;
    }
    previous = relative;
  }
  EXPECT_LT(previous, 1e-5);  // 32 elements per ring
}

}  // namespace
}  // namespace mastrom::fullorder
