// Clamped single-shell structures (see clamped_cylinder.hpp).
#include "tests/support/clamped_cylinder.hpp"

#include <cmath>
#include <memory>

#include "common/error.hpp"
#include "fullorder/bonded_edge.hpp"

namespace mastrom::fullorder {
namespace {

void requirePositive(const char* what, const char* name, double value) {
  MASTROM_REQUIRE(std::isfinite(value) && value > 0.0, InputError, what, ": ", name, " = ", value,
                  " is out of range (must be finite and > 0)");
}

void validateSection(const char* what, const ShellSection& s) {
  requirePositive(what, "thickness_m", s.thickness_m);
  requirePositive(what, "youngs_modulus_pa", s.youngs_modulus_pa);
  requirePositive(what, "density_kg_m3", s.density_kg_m3);
  MASTROM_REQUIRE(s.poisson_ratio > -1.0 && s.poisson_ratio < 0.5, InputError, what,
                  ": poisson_ratio = ", s.poisson_ratio, " is out of range (must be in (-1, 0.5))");
  MASTROM_REQUIRE(std::isfinite(s.damping_s) && s.damping_s >= 0.0, InputError, what,
                  ": damping_s = ", s.damping_s, " is out of range (must be finite and ≥ 0)");
}

void validateCommon(const char* what, int gauss_order, const Eigen::Vector3d& gravity) {
  MASTROM_REQUIRE(gauss_order >= 1 && gauss_order <= 20, InputError, what,
                  ": gauss_order = ", gauss_order, " is out of range (must be in 1..20)");
  MASTROM_REQUIRE(gravity.allFinite(), InputError, what, ": gravity has a non-finite entry");
}

/// Add the mesh, clamp its x = 0 edge to the ground frame (the global frame: the mesh is built in
/// global coordinates), finalize.
ClampedShell assemble(ShellMesh mesh, const ShellSection& section, int gauss_order,
                      const Eigen::Vector3d& gravity) {
  ClampedShell out;
  MultibodySystem& sys = out.system;
  const int first = sys.addShellMesh(mesh, section, gauss_order);
  for (int node : mesh.nodes_x0) {
    const int global = first + node;
    sys.addConstraint(std::make_unique<BondedEdgeNode>(GroundFrame{}, sys.nodeDofOffset(global),
                                                       mesh.nodes[static_cast<size_t>(node)],
                                                       mesh.normals[static_cast<size_t>(node)]));
    out.clamped_nodes.push_back(global);
  }
  for (int node : mesh.nodes_x1) out.free_edge_nodes.push_back(first + node);
  sys.setGravity(gravity);
  sys.finalize();
  out.mesh = std::move(mesh);
  return out;
}

}  // namespace

void validateClampedCylinderParameters(const ClampedCylinderParameters& p) {
  constexpr const char* what = "clamped cylinder";
  requirePositive(what, "radius_m", p.radius_m);
  requirePositive(what, "length_m", p.length_m);
  validateSection(what, p.section);
  MASTROM_REQUIRE(p.section.thickness_m < p.radius_m, InputError, what,
                  ": thickness_m = ", p.section.thickness_m,
                  " is out of range (must be < radius_m = ", p.radius_m, ")");
  MASTROM_REQUIRE(p.elements_axial >= 1, InputError, what, ": elements_axial = ", p.elements_axial,
                  " is out of range (must be ≥ 1)");
  MASTROM_REQUIRE(p.elements_circumferential >= 3, InputError, what,
                  ": elements_circumferential = ", p.elements_circumferential,
                  " is out of range (must be ≥ 3)");
  validateCommon(what, p.gauss_order, p.gravity_m_s2);
}

void validateCantileverPlateParameters(const CantileverPlateParameters& p) {
  constexpr const char* what = "cantilever plate";
  requirePositive(what, "length_m", p.length_m);
  requirePositive(what, "width_m", p.width_m);
  validateSection(what, p.section);
  MASTROM_REQUIRE(p.elements_x >= 1 && p.elements_y >= 1, InputError, what, ": elements (",
                  p.elements_x, ", ", p.elements_y, ") are out of range (must be ≥ 1)");
  validateCommon(what, p.gauss_order, p.gravity_m_s2);
}

ClampedShell buildClampedCylinder(const ClampedCylinderParameters& p) {
  validateClampedCylinderParameters(p);
  return assemble(
      makeCylinderMesh(p.radius_m, p.length_m, p.elements_axial, p.elements_circumferential),
      p.section, p.gauss_order, p.gravity_m_s2);
}

ClampedShell buildCantileverPlate(const CantileverPlateParameters& p) {
  validateCantileverPlateParameters(p);
  return assemble(makeFlatStripMesh(p.length_m, p.width_m, p.elements_x, p.elements_y), p.section,
                  p.gauss_order, p.gravity_m_s2);
}

}  // namespace mastrom::fullorder
