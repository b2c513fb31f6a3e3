// Structured cylinder and strip meshes (see shell_mesh.hpp).
#include "fullorder/shell_mesh.hpp"

#include <cmath>

#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;

Vec9 nodeVector(const Eigen::Vector3d& r, const Eigen::Vector3d& rx, const Eigen::Vector3d& ry) {
  Vec9 e;
  e << r, rx, ry;
  return e;
}
}  // namespace

Vec36 ShellMesh::elementReference(int element) const {
  MASTROM_ASSERT(element >= 0 && element < elementCount());
  Vec36 e;
  for (int c = 0; c < 4; ++c)
    e.segment<9>(9 * c) = nodes[static_cast<size_t>(elements[element][c])];
  return e;
}

ShellMesh makeCylinderMesh(double radius_m, double length_m, int n_axial, int n_circ,
                           const Placement& placement) {
  MASTROM_REQUIRE(std::isfinite(radius_m) && radius_m > 0.0, InputError,
                  "cylinder mesh: radius_m = ", radius_m, " is out of range (must be > 0)");
  MASTROM_REQUIRE(std::isfinite(length_m) && length_m > 0.0, InputError,
                  "cylinder mesh: length_m = ", length_m, " is out of range (must be > 0)");
  MASTROM_REQUIRE(n_axial >= 1, InputError, "cylinder mesh: elements_axial = ", n_axial,
                  " is out of range (must be ≥ 1)");
  // Three elements are the fewest that close a ring with distinct nodes per element.
  MASTROM_REQUIRE(n_circ >= 3, InputError, "cylinder mesh: elements_circumferential = ", n_circ,
                  " is out of range (must be ≥ 3)");

  ShellMesh mesh;
  mesh.side_a_m = length_m / n_axial;
  mesh.side_b_m = kTwoPi * radius_m / n_circ;
  const Eigen::Matrix3d& rot = placement.rotation;

  const int n_nodes = (n_axial + 1) * n_circ;
  mesh.nodes.reserve(static_cast<size_t>(n_nodes));
  mesh.normals.reserve(static_cast<size_t>(n_nodes));
  for (int i = 0; i <= n_axial; ++i) {
    const double x = i * mesh.side_a_m;
    for (int j = 0; j < n_circ; ++j) {
      const double phi = kTwoPi * j / n_circ;
      const double c = std::cos(phi), s = std::sin(phi);
      const Eigen::Vector3d r(x, radius_m * c, radius_m * s);
      const Eigen::Vector3d rx(1.0, 0.0, 0.0);
      const Eigen::Vector3d ry(0.0, -s, c);
      const Eigen::Vector3d normal(0.0, c, s);
      mesh.nodes.push_back(nodeVector(placement.origin + rot * r, rot * rx, rot * ry));
      mesh.normals.push_back(rot * normal);
    }
  }
  auto id = [n_circ](int i, int j) { return i * n_circ + (j % n_circ); };
  for (int i = 0; i < n_axial; ++i) {
    for (int j = 0; j < n_circ; ++j) {
      mesh.elements.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      const int e = static_cast<int>(mesh.elements.size()) - 1;
      if (i == 0) mesh.elements_x0.push_back(e);
      if (i == n_axial - 1) mesh.elements_x1.push_back(e);
    }
  }
  for (int j = 0; j < n_circ; ++j) {
    mesh.nodes_x0.push_back(id(0, j));
    mesh.nodes_x1.push_back(id(n_axial, j));
  }
  return mesh;
}

ShellMesh makeFlatStripMesh(double length_x_m, double width_y_m, int n_x, int n_y) {
  MASTROM_REQUIRE(std::isfinite(length_x_m) && length_x_m > 0.0, InputError,
                  "strip mesh: length_x_m = ", length_x_m, " is out of range (must be > 0)");
  MASTROM_REQUIRE(std::isfinite(width_y_m) && width_y_m > 0.0, InputError,
                  "strip mesh: width_y_m = ", width_y_m, " is out of range (must be > 0)");
  MASTROM_REQUIRE(n_x >= 1 && n_y >= 1, InputError, "strip mesh: elements (", n_x, ", ", n_y,
                  ") are out of range (must be ≥ 1)");

  ShellMesh mesh;
  mesh.side_a_m = length_x_m / n_x;
  mesh.side_b_m = width_y_m / n_y;
  const Eigen::Vector3d ex(1.0, 0.0, 0.0), ey(0.0, 1.0, 0.0), ez(0.0, 0.0, 1.0);
  for (int i = 0; i <= n_x; ++i) {
    for (int j = 0; j <= n_y; ++j) {
      mesh.nodes.push_back(
          nodeVector(Eigen::Vector3d(i * mesh.side_a_m, j * mesh.side_b_m, 0.0), ex, ey));
      mesh.normals.push_back(ez);
    }
  }
  auto id = [n_y](int i, int j) { return i * (n_y + 1) + j; };
  for (int i = 0; i < n_x; ++i) {
    for (int j = 0; j < n_y; ++j) {
      mesh.elements.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      const int e = static_cast<int>(mesh.elements.size()) - 1;
      if (i == 0) mesh.elements_x0.push_back(e);
      if (i == n_x - 1) mesh.elements_x1.push_back(e);
    }
  }
  for (int j = 0; j <= n_y; ++j) {
    mesh.nodes_x0.push_back(id(0, j));
    mesh.nodes_x1.push_back(id(n_x, j));
  }
  return mesh;
}

}  // namespace mastrom::fullorder
