#include "rom/model/modal_extraction.hpp"

#include "common/error.hpp"
#include "modes/modal_projections.hpp"
#include "rom/model/modal_stress_extraction.hpp"

namespace mastrom::rom {

ModalModel extractModalModel(const fullorder::MastModel& model, const LinearizedModes& lin) {
  const fullorder::MultibodySystem& sys = model.system();
  const Eigen::Index n = sys.dofCount(), k = lin.modes.cols();
  MASTROM_REQUIRE(lin.q_reference.size() == n && lin.modes.rows() == n && lin.mass.rows() == n &&
                      lin.omega_squared.size() == k && k >= 1,
                  InputError, "modal extraction: sizes disagree (", n, " DOFs, ", k, " modes)");
  modes::ModalProjections p =
      modes::projectModes(sys, lin.mass, lin.damping, lin.q_reference, lin.omega_squared,
                          lin.modes, model.endModule());

  ModalModel mm;
  mm.omega_rad_s = std::move(p.omega_rad_s);
  mm.damping_ratio = std::move(p.damping_ratio);
  mm.rotation_participation = std::move(p.rotation_participation);
  mm.centrifugal_participation = std::move(p.centrifugal_participation);
  mm.momentum_participation = std::move(p.translation_participation);
  mm.coriolis = std::move(p.coriolis);
  mm.end_rotation = std::move(p.end_rotation);
  mm.end_translation = std::move(p.end_translation);

  // Rigid data of q̄.
  mm.inertia_z_kg_m2 = p.inertia_z_kg_m2;
  mm.total_mass_kg = sys.totalMass();
  Eigen::Vector3d first_moment;
  for (int i = 0; i < 3; ++i)
    first_moment[i] = sys.uniformField(Eigen::Vector3d::Unit(i)).dot(lin.mass * lin.q_reference);
  mm.centroid_m = first_moment / mm.total_mass_kg;
  // The end point is the last module's centroid (docs/theory.md §2.6).
  const int end = model.endModule();
  mm.end_position_m.noalias() =
      sys.body(end).centroidMap() * lin.q_reference.segment<12>(model.moduleDofOffset(end));
  mm.reference_angle_rad = lin.reference_angle_rad;
  mm.gravity_m_s2 = sys.gravity();
  if (lin.problem)
    mm.stress = extractModalStress(model, *lin.problem, lin.q_reference, lin.modes, lin.omega_squared);
  mm.validate();
  return mm;
}

}  // namespace mastrom::rom
