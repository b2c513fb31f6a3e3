// Structured meshes of gradient-deficient ANCF shell elements (docs/theory.md §2.2, §2.3).
//
// A mesh is a list of nodes, each with its reference nodal vector e₀ = [r, r_x, r_y] ∈ R⁹ and its
// reference unit normal, and a list of a × b elements given by four node ids in the corner order of
// fullorder/shell_shape.hpp (1 = (x−, y−), 2 = (x+, y−), 3 = (x+, y+), 4 = (x−, y+)). All elements
// of one mesh share the side lengths a (along x) and b (along y). The two edges x = 0 and x = L
// (the end rings of a cylinder, the clamped and loaded ends of a strip) are listed as node sets
// and, for edge loads, as the elements that touch them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace mastrom::fullorder {

using Vec9 = Eigen::Matrix<double, 9, 1>;
using Vec36 = Eigen::Matrix<double, 36, 1>;

/// Rigid placement of a mesh: global = origin + rotation · local (rotation columns = local axes).
struct Placement {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
};

struct ShellMesh {
  double side_a_m = 0.0;  ///< element side along the parameter x [m]
  double side_b_m = 0.0;  ///< element side along the parameter y [m]

  std::vector<Vec9> nodes;                   ///< reference e₀ = [r, r_x, r_y] per node (global)
  std::vector<Eigen::Vector3d> normals;      ///< reference unit normal per node (see makers)
  std::vector<std::array<int, 4>> elements;  ///< node ids, corner order of shell_shape.hpp

  std::vector<int> nodes_x0;     ///< nodes on the edge x = 0 (in order of increasing y)
  std::vector<int> nodes_x1;     ///< nodes on the edge x = L
  std::vector<int> elements_x0;  ///< elements whose side ξ = −1 lies on x = 0
  std::vector<int> elements_x1;  ///< elements whose side ξ = +1 lies on x = L

  int nodeCount() const { return static_cast<int>(nodes.size()); }
  int elementCount() const { return static_cast<int>(elements.size()); }
  /// Reference element vector e₀ ∈ R³⁶ of element `element` (corner blocks of nine).
  Vec36 elementReference(int element) const;
};

/// Closed circular cylinder, mid-surface radius R, length L, N_axial × N_circ elements.
///
/// Local (interface) frame: axis along x. Node (i, j), i = 0..N_axial, j = 0..N_circ−1, sits at
/// x = i·a, φ = j·2π/N_circ with r = (x, R cos φ, R sin φ), r_x = (1, 0, 0), r_y = (0, −sin φ, cos
/// φ), normal = (0, cos φ, sin φ) radially outward (note: this is −g_x × g_y; the bonded edge only
/// uses the normal's direction, never its sign). Node id = i·N_circ + j, so ring i is a contiguous
/// block. Periodic: element (i, N_circ−1) closes the ring on nodes j = N_circ−1 and j = 0. a =
/// L/N_axial, b = 2πR/N_circ (arc length). Everything is then placed rigidly by `placement`.
ShellMesh makeCylinderMesh(double radius_m, double length_m, int n_axial, int n_circ,
                           const Placement& placement = {});

/// Flat strip [0, Lx] × [0, Ly] in the global x–y plane, normal +z, Nx × Ny elements.
/// Node (i, j) at (i·a, j·b, 0), id = i·(Ny+1) + j, r_x = (1, 0, 0), r_y = (0, 1, 0).
ShellMesh makeFlatStripMesh(double length_x_m, double width_y_m, int n_x, int n_y);

}  // namespace mastrom::fullorder
