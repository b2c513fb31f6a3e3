// Structured shell meshes (fullorder/shell_mesh.hpp): counts, periodicity, reference nodal data,
// and the reference area of the interpolated cylinder against an independent 1-D computation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <set>

#include "common/error.hpp"
#include "fullorder/shell_element.hpp"
#include "fullorder/shell_mesh.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Matrix3d someRotation() {
  return (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
          Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

TEST(CylinderMesh, CountsRingsAndPeriodicity) {
  const int na = 3, nc = 8;
  const ShellMesh mesh = makeCylinderMesh(0.041, 0.05, na, nc);
  EXPECT_EQ(mesh.nodeCount(), (na + 1) * nc);
  EXPECT_EQ(mesh.elementCount(), na * nc);
  ASSERT_EQ(mesh.nodes_x0.size(), static_cast<size_t>(nc));
  ASSERT_EQ(mesh.nodes_x1.size(), static_cast<size_t>(nc));
  EXPECT_EQ(mesh.elements_x0.size(), static_cast<size_t>(nc));
  EXPECT_EQ(mesh.elements_x1.size(), static_cast<size_t>(nc));
  EXPECT_DOUBLE_EQ(mesh.side_a_m, 0.05 / na);
  EXPECT_DOUBLE_EQ(mesh.side_b_m, 2.0 * kPi * 0.041 / nc);
  for (int e = 0; e < mesh.elementCount(); ++e) {
    const auto& c = mesh.elements[static_cast<size_t>(e)];
    EXPECT_EQ(std::set<int>(c.begin(), c.end()).size(), 4u) << "element " << e;
  }
  // The last element of every ring closes on the first: its y+ corners are the y− corners of j = 0.
  for (int i = 0; i < na; ++i) {
    const auto& first = mesh.elements[static_cast<size_t>(i * nc)];
    const auto& last = mesh.elements[static_cast<size_t>(i * nc + nc - 1)];
    EXPECT_EQ(last[2], first[1]);
    EXPECT_EQ(last[3], first[0]);
  }
  // Every node belongs to exactly 2 (end rings) or 4 (interior rings) elements: no seam duplicates.
  std::vector<int> uses(static_cast<size_t>(mesh.nodeCount()), 0);
  for (const auto& c : mesh.elements)
    for (int n : c) ++uses[static_cast<size_t>(n)];
  for (int n = 0; n < mesh.nodeCount(); ++n) {
    const bool end_ring = n < nc || n >= na * nc;
    EXPECT_EQ(uses[static_cast<size_t>(n)], end_ring ? 2 : 4) << "node " << n;
  }
}

TEST(CylinderMesh, ReferenceNodalDataOnPlacedCylinder) {
  const double radius = 0.041, length = 0.05;
  Placement placement;
  placement.origin = Eigen::Vector3d(0.3, -0.2, 0.1);
  placement.rotation = someRotation();
  const ShellMesh mesh = makeCylinderMesh(radius, length, 2, 8, placement);
  const Eigen::Vector3d axis = placement.rotation.col(0);
  for (int n = 0; n < mesh.nodeCount(); ++n) {
    const Vec9& e = mesh.nodes[static_cast<size_t>(n)];
    const Eigen::Vector3d r = e.head<3>(), rx = e.segment<3>(3), ry = e.tail<3>();
    const Eigen::Vector3d nrm = mesh.normals[static_cast<size_t>(n)];
    const Eigen::Vector3d rel = r - placement.origin;
    const double x = rel.dot(axis);
    const Eigen::Vector3d radial = rel - x * axis;
    // Round-off tolerances: all quantities are O(1) or O(R) computed with a few flops.
    EXPECT_NEAR(radial.norm(), radius, 1e-15);
    EXPECT_NEAR(x / mesh.side_a_m, std::round(x / mesh.side_a_m), 1e-12);  // on a ring x = i·a
    EXPECT_LT((rx - axis).norm(), 1e-15);
    EXPECT_NEAR(ry.norm(), 1.0, 1e-15);
    EXPECT_NEAR(ry.dot(axis), 0.0, 1e-15);
    EXPECT_NEAR(ry.dot(radial), 0.0, 1e-16);
    EXPECT_LT((nrm - radial / radius).norm(), 1e-14);
    // r_y turns positively about the axis: axis · (normal × r_y) = +1.
    EXPECT_NEAR(axis.dot(nrm.cross(ry)), 1.0, 1e-15);
  }
  // Ring membership and angular spacing on the x = 0 ring: φ_j = 2πj/8 from the local y axis.
  for (size_t j = 0; j < mesh.nodes_x0.size(); ++j) {
    const Eigen::Vector3d local =
        placement.rotation.transpose() *
        (mesh.nodes[static_cast<size_t>(mesh.nodes_x0[j])].head<3>() - placement.origin);
    EXPECT_NEAR(local.x(), 0.0, 1e-15);
    EXPECT_NEAR(std::atan2(local.z(), local.y()), std::remainder(2.0 * kPi * j / 8, 2.0 * kPi),
                1e-14);
    const Eigen::Vector3d local1 =
        placement.rotation.transpose() *
        (mesh.nodes[static_cast<size_t>(mesh.nodes_x1[j])].head<3>() - placement.origin);
    EXPECT_NEAR(local1.x(), length, 1e-15);
  }
}

/// Independent reference: length of the cubic Hermite interpolant of a circular arc of angle Δ on a
/// unit circle, with end tangents of length b = Δ (arc-length parametrisation), by 400-point
/// composite Gauss (error ≪ 1e-12).
double hermiteArcLength(double delta) {
  const Eigen::Vector2d p0(1.0, 0.0), p1(std::cos(delta), std::sin(delta));
  const Eigen::Vector2d t0(0.0, 1.0), t1(-std::sin(delta), std::cos(delta));
  const double b = delta;
  const double gp[2] = {-1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)};
  const int panels = 200;
  double length = 0.0;
  for (int p = 0; p < panels; ++p) {
    for (double g : gp) {
      const double tau = (p + 0.5 * (1.0 + g)) / panels;
      const double dh00 = 6 * tau * tau - 6 * tau, dh10 = 3 * tau * tau - 4 * tau + 1;
      const double dh11 = 3 * tau * tau - 2 * tau;
      const Eigen::Vector2d dc = (dh00 * (p0 - p1) + dh10 * b * t0 + dh11 * b * t1) / b;
      length += 0.5 * b / panels * dc.norm();
    }
  }
  return length;
}

TEST(CylinderMesh, ReferenceAreaIsTheInterpolatedCylinder) {
  // The incomplete bicubic reproduces x linearly and, with data independent of x, its y-part
  // reduces to the 1-D cubic Hermite interpolant (sum of docs/theory.md §2.2's functions over ξ_i =
  // ±1), so the reference surface is the ruled cylinder over the Hermite ring: area = L · N_circ ·
  // ℓ_H · R.
  const double radius = 0.041, length = 0.05;
  double previous_error = 0.0;
  for (int nc : {8, 16}) {
    ShellSection section;
    const ShellMesh mesh = makeCylinderMesh(radius, length, 2, nc);
    double area = 0.0;
    for (int e = 0; e < mesh.elementCount(); ++e)
      area += ShellElement(mesh.side_a_m, mesh.side_b_m, mesh.elementReference(e), section)
                  .referenceArea();
    const double hermite = length * nc * radius * hermiteArcLength(2.0 * kPi / nc);
    const double exact = 2.0 * kPi * radius * length;
    // 5×5 Gauss integrates the smooth, nearly constant |G_x × G_y| far below 1e-9 relative.
    EXPECT_NEAR(area / hermite - 1.0, 0.0, 1e-9) << "N_circ = " << nc;
    // Interpolation error of the ring: O(Δφ⁴), measured −5.2e-4 at N_circ = 8, −3.3e-5 at 16.
    const double error = area / exact - 1.0;
    EXPECT_LT(std::abs(error), nc == 8 ? 6e-4 : 4e-5) << "N_circ = " << nc;
    if (nc == 16) {
      EXPECT_GT(previous_error / error, 14.0);  // fourth order: ratio 2⁴ = 16
      EXPECT_LT(previous_error / error, 18.0);
    }
    previous_error = error;
  }
}

TEST(FlatStripMesh, CountsEdgesAndNodalData) {
  const ShellMesh mesh = makeFlatStripMesh(0.1, 0.01, 4, 2);
  EXPECT_EQ(mesh.nodeCount(), 5 * 3);
  EXPECT_EQ(mesh.elementCount(), 4 * 2);
  ASSERT_EQ(mesh.nodes_x0.size(), 3u);
  ASSERT_EQ(mesh.nodes_x1.size(), 3u);
  EXPECT_EQ(mesh.elements_x1.size(), 2u);
  for (int n : mesh.nodes_x0) EXPECT_DOUBLE_EQ(mesh.nodes[static_cast<size_t>(n)][0], 0.0);
  for (int n : mesh.nodes_x1) EXPECT_NEAR(mesh.nodes[static_cast<size_t>(n)][0], 0.1, 1e-16);
  for (int e : mesh.elements_x1) {
    // Corners 2 and 3 (the ξ = +1 side) lie on x = Lx.
    EXPECT_NEAR(mesh.nodes[static_cast<size_t>(mesh.elements[static_cast<size_t>(e)][1])][0], 0.1,
                1e-16);
    EXPECT_NEAR(mesh.nodes[static_cast<size_t>(mesh.elements[static_cast<size_t>(e)][2])][0], 0.1,
                1e-16);
  }
  double area = 0.0;
  ShellSection section;
  for (int e = 0; e < mesh.elementCount(); ++e) {
    const Vec36 e0 = mesh.elementReference(e);
    // Corner geometry: corner 1 → 2 along +x by a, corner 1 → 4 along +y by b.
    EXPECT_NEAR((e0.segment<3>(9) - e0.segment<3>(0) - Eigen::Vector3d(mesh.side_a_m, 0, 0)).norm(),
                0.0, 1e-16);
    EXPECT_NEAR(
        (e0.segment<3>(27) - e0.segment<3>(0) - Eigen::Vector3d(0, mesh.side_b_m, 0)).norm(), 0.0,
        1e-16);
    area += ShellElement(mesh.side_a_m, mesh.side_b_m, e0, section).referenceArea();
  }
  EXPECT_NEAR(area, 0.1 * 0.01, 1e-15);  // flat: exact
  for (const Eigen::Vector3d& n : mesh.normals) EXPECT_EQ(n, Eigen::Vector3d::UnitZ());
}

TEST(Meshes, RejectBadInput) {
  EXPECT_THROW(makeCylinderMesh(-1.0, 0.05, 2, 8), InputError);
  EXPECT_THROW(makeCylinderMesh(0.04, 0.05, 0, 8), InputError);
  EXPECT_THROW(makeCylinderMesh(0.04, 0.05, 2, 2), InputError);
  EXPECT_THROW(makeFlatStripMesh(0.1, 0.0, 2, 1), InputError);
}

}  // namespace
}  // namespace mastrom::fullorder
