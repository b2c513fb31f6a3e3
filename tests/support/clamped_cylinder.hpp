// Single-shell benchmark structures clamped to a fixed ground frame along one edge: a cylindrical
// interface bonded at x = 0 and free at x = L, and a flat plate clamped along x = 0 (a cantilever).
// They exist for the modal convergence studies of the shell element against thin-shell and
// Kirchhoff-plate references (tests/modes/test_plate_cylinder.cpp, benchmarks/bench_modes_*), and
// as the "interface with a free end" the mast itself never has.
//
// The clamp is the bonded edge of docs/theory.md §2.3 with a constant (ground) flange, exactly as
// in tests/fullorder/test_static_strip.cpp: seven linear equations per clamped node fix the
// position r, the edge tangent r_y and the wall's slope across the edge (r_x · n⁰ = 0); r_x stays
// free in the tangent plane, so the wall may still stretch axially and shear at the edge. For a
// plate this is the Kirchhoff clamp w = 0, ∂w/∂x = 0 (and u = v = 0 along the edge); for a cylinder
// the classical clamped end of thin-shell theory with the axial displacement fixed at the
// mid-surface.
//
// No rigid bodies: the DOF vector is the shell nodes' 9-blocks only (global node k at 9k).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "fullorder/multibody_system.hpp"
#include "fullorder/shell_element.hpp"
#include "fullorder/shell_mesh.hpp"

namespace mastrom::fullorder {

/// A finalized system holding one clamped shell mesh, with the mesh's bookkeeping.
struct ClampedShell {
  MultibodySystem system;
  ShellMesh mesh;                    ///< the mesh as added (mesh node k = global node k)
  std::vector<int> clamped_nodes;    ///< global ids of the nodes on the clamped edge x = 0
  std::vector<int> free_edge_nodes;  ///< global ids of the nodes on the opposite edge x = L
};

/// Clamped–free circular cylinder, axis along global +X from the origin (docs/theory.md §2.2 mesh).
struct ClampedCylinderParameters {
  double radius_m = 0.041;  ///< mid-surface radius R
  double length_m = 0.30;   ///< L
  int elements_axial = 8;
  int elements_circumferential = 16;
  ShellSection section;  ///< thickness, E, ν, ρ, μ (defaults: the mast's aluminium, μ = 0)
  int gauss_order = 5;
  Eigen::Vector3d gravity_m_s2 = Eigen::Vector3d::Zero();
};

/// Flat plate [0, a] × [0, b] in the global x–y plane (normal +z), clamped along x = 0.
struct CantileverPlateParameters {
  double length_m = 0.1;  ///< a, along x (away from the clamp)
  double width_m = 0.1;   ///< b, along y (the clamped edge)
  int elements_x = 8;
  int elements_y = 8;
  ShellSection section;
  int gauss_order = 5;
  Eigen::Vector3d gravity_m_s2 = Eigen::Vector3d::Zero();
};

/// Throws InputError naming the parameter, value and allowed range.
void validateClampedCylinderParameters(const ClampedCylinderParameters& params);
void validateCantileverPlateParameters(const CantileverPlateParameters& params);

/// Build and finalize the clamped–free cylinder. Throws InputError on bad parameters.
ClampedShell buildClampedCylinder(const ClampedCylinderParameters& params);

/// Build and finalize the cantilever plate. Throws InputError on bad parameters.
ClampedShell buildCantileverPlate(const CantileverPlateParameters& params);

}  // namespace mastrom::fullorder
