// Mast assembly (see mast_model.hpp; docs/theory.md §1, §2.3, §2.4).
#include "fullorder/mast_model.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <memory>

#include "common/error.hpp"
#include "fullorder/block_rotation.hpp"
#include "fullorder/bonded_edge.hpp"
#include "fullorder/shell_mesh.hpp"

namespace mastrom::fullorder {
namespace {

void requirePositive(double value, const char* name) {
  MASTROM_REQUIRE(std::isfinite(value) && value > 0.0, InputError, "mast: ", name, " = ", value,
                  " is out of range (must be finite and > 0)");
}

}  // namespace

void validateMastParameters(const MastParameters& p) {
  MASTROM_REQUIRE(p.modules >= 2, InputError, "mast: modules = ", p.modules,
                  " is out of range (must be ≥ 2)");
  requirePositive(p.module_side_m, "module_side_m");
  requirePositive(p.module_mass_kg, "module_mass_kg");
  requirePositive(p.interface_length_m, "interface_length_m");
  requirePositive(p.interface_radius_m, "interface_radius_m");
  requirePositive(p.interface_thickness_m, "interface_thickness_m");
  MASTROM_REQUIRE(p.interface_thickness_m < p.interface_radius_m, InputError,
                  "mast: interface_thickness_m = ", p.interface_thickness_m,
                  " is out of range (must be < interface_radius_m = ", p.interface_radius_m, ")");
  MASTROM_REQUIRE(p.elements_axial >= 1, InputError, "mast: elements_axial = ", p.elements_axial,
                  " is out of range (must be ≥ 1)");
  MASTROM_REQUIRE(p.elements_circumferential >= 3, InputError,
                  "mast: elements_circumferential = ", p.elements_circumferential,
                  " is out of range (must be ≥ 3)");
  requirePositive(p.youngs_modulus_pa, "youngs_modulus_pa");
  MASTROM_REQUIRE(p.poisson_ratio > -1.0 && p.poisson_ratio < 0.5, InputError,
                  "mast: poisson_ratio = ", p.poisson_ratio,
                  " is out of range (must be in (-1, 0.5))");
  requirePositive(p.density_kg_m3, "density_kg_m3");
  MASTROM_REQUIRE(std::isfinite(p.damping_s) && p.damping_s >= 0.0, InputError,
                  "mast: damping_s = ", p.damping_s, " is out of range (must be finite and ≥ 0)");
  MASTROM_REQUIRE(p.gauss_order >= 1 && p.gauss_order <= 20, InputError,
                  "mast: gauss_order = ", p.gauss_order, " is out of range (must be in 1..20)");
  MASTROM_REQUIRE(p.gravity_m_s2.allFinite(), InputError, "mast: gravity has a non-finite entry");
  if (p.lock_angle_rad)
    MASTROM_REQUIRE(std::isfinite(*p.lock_angle_rad), InputError,
                    "mast: lock_angle_rad = ", *p.lock_angle_rad, " is not finite");
}

MastModel buildMast(const MastParameters& params) {
  validateMastParameters(params);
  MastModel model;
  model.params_ = params;
  MultibodySystem& sys = model.system_;

  const double d = params.module_side_m;
  const double pitch = params.module_side_m + params.interface_length_m;
  const Eigen::Matrix3d inertia =
      params.module_inertia_kg_m2.value_or(RigidModule::boxInertia(params.module_mass_kg, d, d, d));
  std::vector<RigidModule> modules;
  std::vector<Vec12> module_reference;
  for (int k = 0; k < params.modules; ++k) {
    modules.emplace_back(d, params.module_mass_kg, inertia);
    module_reference.push_back(modules.back().coordinates(Eigen::Vector3d(k * pitch, 0.0, 0.0),
                                                          Eigen::Matrix3d::Identity()));
    sys.addRigidBody(modules.back(), module_reference.back());
  }

  // Base joint and drive on module 0.
  std::unique_ptr<BaseJoint> joint =
      params.lock_angle_rad
          ? std::make_unique<BaseJoint>(sys.bodyDofOffset(0), d,
                                        LockedAngle{*params.lock_angle_rad})
          : std::make_unique<BaseJoint>(sys.bodyDofOffset(0), d, DriveLaw(params.drive));
  model.joint_ = joint.get();
  model.joint_offset_ = sys.addConstraint(std::move(joint));

  ShellSection section;
  section.thickness_m = params.interface_thickness_m;
  section.youngs_modulus_pa = params.youngs_modulus_pa;
  section.poisson_ratio = params.poisson_ratio;
  section.density_kg_m3 = params.density_kg_m3;
  section.damping_s = params.damping_s;

  for (int k = 0; k + 1 < params.modules; ++k) {
    Placement placement;
    placement.origin = Eigen::Vector3d(k * pitch + 0.5 * d, 0.0, 0.0);
    const ShellMesh mesh =
        makeCylinderMesh(params.interface_radius_m, params.interface_length_m,
                         params.elements_axial, params.elements_circumferential, placement);
    const int first = sys.addShellMesh(mesh, section, params.gauss_order);
    MastModel::InterfaceRange range;
    range.first_node = first;
    range.node_count = mesh.nodeCount();
    range.first_dof = sys.nodeDofOffset(first);
    range.dof_count = 9 * mesh.nodeCount();
    auto bond = [&](const std::vector<int>& ring, int module, std::vector<int>& ids) {
      for (int node : ring) {
        const int global = first + node;
        ids.push_back(global);
        sys.addConstraint(std::make_unique<BondedEdgeNode>(
            modules[static_cast<size_t>(module)], sys.bodyDofOffset(module),
            module_reference[static_cast<size_t>(module)], sys.nodeDofOffset(global),
            mesh.nodes[static_cast<size_t>(node)], mesh.normals[static_cast<size_t>(node)]));
      }
    };
    bond(mesh.nodes_x0, k, range.ring0_nodes);
    bond(mesh.nodes_x1, k + 1, range.ring1_nodes);
    model.interfaces_.push_back(std::move(range));
  }
  sys.setGravity(params.gravity_m_s2);
  sys.finalize();
  return model;
}

Eigen::Vector3d MastModel::jointForce(const Eigen::Ref<const Eigen::VectorXd>& lambda) const {
  return BaseJoint::jointForce(lambda.segment<BaseJoint::kEquations>(joint_offset_));
}

double MastModel::driveTorque(const Eigen::Ref<const Eigen::VectorXd>& lambda) const {
  return BaseJoint::driveTorque(lambda.segment<BaseJoint::kEquations>(joint_offset_));
}

Eigen::VectorXd MastModel::rotatedReference(double angle_rad) const {
  return system_.rotated(system_.referenceCoordinates(), rotationAboutZ(angle_rad));
}

void MastModel::initialState(Eigen::VectorXd& q, Eigen::VectorXd& qdot) const {
  const DriveState start = joint_->driveAt(0.0);
  q = rotatedReference(start.angle_rad);
  qdot.resize(q.size());
  const Eigen::Vector3d omega(0.0, 0.0, start.rate_rad_s);
  for (Eigen::Index k = 0; k < q.size() / 3; ++k)
    qdot.segment<3>(3 * k) = omega.cross(Eigen::Vector3d(q.segment<3>(3 * k)));
}

}  // namespace mastrom::fullorder
