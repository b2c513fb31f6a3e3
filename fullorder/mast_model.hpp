// The mast: n rigid modules joined by n − 1 cylindrical-shell interfaces, driven at the base
// (docs/theory.md §1, §2.3, §2.4). buildMast() turns MastParameters into a finalized
// MultibodySystem plus the bookkeeping every consumer needs (DOF ranges, multiplier indices of the
// joint force and drive torque, the initial state). The TOML config is mapped to MastParameters
// elsewhere; this file does not read files.
//
// Stowed geometry (θ = 0): the mast axis is global +X. Module k (k = 0 … n−1 here, "module k+1" in
// the paper's numbering) has its centroid at (k (d + L), 0, 0) and the global orientation.
// Interface k runs from module k's +x face (local x = d/2) to module k+1's −x face; its interface
// frame has its origin at the centroid of module k + (d/2, 0, 0) and its axis along X. Both end
// rings are bonded (docs/theory.md §2.3), the base joint and drive (or a lock at θ₀) act on module
// 0. DOF layout: modules' 12-blocks first (module k at 12k), then interface k's nodes, ring by
// ring.
// Multipliers: module k's internal constraints (6 each, in module order), then the base joint (6),
// then the bonded-edge nodes (7 each; interface by interface, x = 0 ring then x = L ring).
#pragma once

#include <Eigen/Core>
#include <optional>

#include "fullorder/base_joint.hpp"
#include "fullorder/drive_law.hpp"
#include "fullorder/multibody_system.hpp"

namespace mastrom::fullorder {

struct MastParameters {
  int modules = 4;              ///< n ≥ 2 (Scheme 1/2/3 = 2/3/4)
  double module_side_m = 0.10;  ///< d, also the NCF axis length
  double module_mass_kg = 0.50;
  /// Centroidal inertia in the module frame; default: solid cube m d²/6 · I.
  std::optional<Eigen::Matrix3d> module_inertia_kg_m2;
  double interface_length_m = 0.05;      ///< L
  double interface_radius_m = 0.041;     ///< R, mid-surface
  double interface_thickness_m = 0.002;  ///< h
  int elements_axial = 2;
  int elements_circumferential = 8;
  double youngs_modulus_pa = 70e9;
  double poisson_ratio = 0.33;
  double density_kg_m3 = 2700.0;
  double damping_s = 1e-5;  ///< Kelvin–Voigt μ
  /// Shell quadrature points per direction. 4×4 integrates the mass exactly (docs/theory.md §2.2)
  /// and changes the mast's modes (bending, torsion, axial, rocking: the ones a deployment excites)
  /// by < 3e-7 relative against 5×5 on the default mesh (tests/modes/test_quadrature_order.cpp);
  /// only ~10 kHz shell modes move by up to 1e-3. It costs 36 % less per force evaluation than 5×5.
  int gauss_order = 4;
  Eigen::Vector3d gravity_m_s2 = Eigen::Vector3d::Zero();
  DriveLawParameters drive;
  std::optional<double> lock_angle_rad;  ///< set: joint locked at θ₀ (statics, modes)
};

/// Check every parameter's range; throws InputError naming the parameter, value and range.
void validateMastParameters(const MastParameters& params);

class MastModel {
public:
  /// Global node range and DOF range of one interface.
  struct InterfaceRange {
    int first_node = 0;
    int node_count = 0;
    int first_dof = 0;
    int dof_count = 0;
    std::vector<int> ring0_nodes;  ///< global ids of the x = 0 ring (bonded to module k)
    std::vector<int> ring1_nodes;  ///< global ids of the x = L ring (bonded to module k + 1)
  };

  const MastParameters& parameters() const { return params_; }
  const MultibodySystem& system() const { return system_; }
  MultibodySystem& system() { return system_; }

  int moduleCount() const { return params_.modules; }
  int interfaceCount() const { return params_.modules - 1; }
  int endModule() const { return params_.modules - 1; }
  int moduleDofOffset(int k) const { return system_.bodyDofOffset(k); }
  const InterfaceRange& interfaceRange(int k) const { return interfaces_[static_cast<size_t>(k)]; }
  int dofCount() const { return system_.dofCount(); }
  int constraintCount() const { return system_.constraintCount(); }
  double totalMass() const { return system_.totalMass(); }

  /// Multiplier index of the base joint's first pin row (three consecutive: x, y, z).
  int jointForceMultiplier() const { return joint_offset_ + BaseJoint::kPinRow; }
  /// Multiplier index of the driving constraint.
  int driveTorqueMultiplier() const { return joint_offset_ + BaseJoint::kDriveRow; }
  /// Multiplier offset of the base-joint block (six rows).
  int jointMultiplierOffset() const { return joint_offset_; }
  /// Force of the joint on module 0 (the paper's module 1) [N], global frame.
  Eigen::Vector3d jointForce(const Eigen::Ref<const Eigen::VectorXd>& lambda) const;
  /// Torque of the drive on module 0 about +Z [N·m].
  double driveTorque(const Eigen::Ref<const Eigen::VectorXd>& lambda) const;
  const BaseJoint& baseJoint() const { return *joint_; }

  /// Initial state: the stowed reference rotated about Z by θ(0) (or θ₀ when locked), velocity of
  /// the rigid rotation at θ̇(0): q̇ = θ̇ Z × (every 3-block of q).
  void initialState(Eigen::VectorXd& q, Eigen::VectorXd& qdot) const;
  /// The stowed reference rotated rigidly about Z by `angle_rad`.
  Eigen::VectorXd rotatedReference(double angle_rad) const;

private:
  friend MastModel buildMast(const MastParameters& params);
  MastModel() = default;

  MastParameters params_;
  MultibodySystem system_;
  std::vector<InterfaceRange> interfaces_;
  int joint_offset_ = 0;
  const BaseJoint* joint_ = nullptr;  ///< borrowed from system_ (owned there, address stable)
};

/// Build and finalize the mast. Throws InputError on bad parameters.
MastModel buildMast(const MastParameters& params);

}  // namespace mastrom::fullorder
