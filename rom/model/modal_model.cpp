#include "rom/model/modal_model.hpp"

#include "common/error.hpp"

namespace mastrom::rom {

void ModalModel::validate() const {
  const Eigen::Index k = omega_rad_s.size();
  MASTROM_REQUIRE(k >= 1, InputError, "modal model: no modes");
  MASTROM_REQUIRE(damping_ratio.size() == k && rotation_participation.size() == k &&
                      centrifugal_participation.size() == k && end_rotation.cols() == k &&
                      end_translation.cols() == k && momentum_participation.cols() == k &&
                      (coriolis.size() == 0 || (coriolis.rows() == k && coriolis.cols() == k)),
                  InputError, "modal model: per-mode arrays disagree in size (", k, " modes)");
  MASTROM_REQUIRE(omega_rad_s.allFinite() && damping_ratio.allFinite() &&
                      rotation_participation.allFinite() && centrifugal_participation.allFinite() &&
                      end_rotation.allFinite() && end_translation.allFinite() &&
                      momentum_participation.allFinite() && coriolis.allFinite(),
                  InputError, "modal model: non-finite modal data");
  MASTROM_REQUIRE((omega_rad_s.array() >= 0).all() && (damping_ratio.array() >= 0).all(),
                  InputError, "modal model: negative frequency or damping ratio");
  MASTROM_REQUIRE(total_mass_kg > 0 && inertia_z_kg_m2 > 0, InputError,
                  "modal model: mass ", total_mass_kg, " kg and inertia ", inertia_z_kg_m2,
                  " kg m^2 must be > 0");
  stress.validate(static_cast<int>(k), /*check_values=*/false);  // see ModalStress::validate
}

void ModalModel::resizeModes(Eigen::Index k, bool coriolis_matrix) {
  omega_rad_s.resize(k);
  damping_ratio.resize(k);
  rotation_participation.resize(k);
  centrifugal_participation.resize(k);
  end_rotation.resize(3, k);
  end_translation.resize(3, k);
  momentum_participation.resize(3, k);
  coriolis.resize(coriolis_matrix ? k : 0, coriolis_matrix ? k : 0);
}

namespace {

/// `out` with the rigid data of `m` and room for k modes in every per-mode field but the Coriolis
/// matrix (left empty).
ModalModel rigidWithRoomFor(const ModalModel& m, Eigen::Index k) {
  ModalModel out;
  out.resizeModes(k, false);
  out.inertia_z_kg_m2 = m.inertia_z_kg_m2;
  out.total_mass_kg = m.total_mass_kg;
  out.centroid_m = m.centroid_m;
  out.end_position_m = m.end_position_m;
  out.reference_angle_rad = m.reference_angle_rad;
  out.gravity_m_s2 = m.gravity_m_s2;
  return out;
}

}  // namespace

ModalModel selectModes(const ModalModel& m, const std::vector<int>& modes) {
  const auto k = static_cast<Eigen::Index>(modes.size());
  for (const int i : modes)
    MASTROM_REQUIRE(i >= 0 && i < m.modeCount(), InputError, "modal model: mode ", i,
                    " selected from ", m.modeCount());
  ModalModel out = rigidWithRoomFor(m, k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const Eigen::Index i = modes[static_cast<std::size_t>(j)];
    out.omega_rad_s[j] = m.omega_rad_s[i];
    out.damping_ratio[j] = m.damping_ratio[i];
    out.rotation_participation[j] = m.rotation_participation[i];
    out.centrifugal_participation[j] = m.centrifugal_participation[i];
    out.end_rotation.col(j) = m.end_rotation.col(i);
    out.end_translation.col(j) = m.end_translation.col(i);
    out.momentum_participation.col(j) = m.momentum_participation.col(i);
  }
  if (m.coriolis.size() != 0) {
    out.coriolis.resize(k, k);
    for (Eigen::Index a = 0; a < k; ++a)
      for (Eigen::Index b = 0; b < k; ++b)
        out.coriolis(a, b) = m.coriolis(modes[static_cast<std::size_t>(a)],
                                        modes[static_cast<std::size_t>(b)]);
  }
  return out;
}

ModalModel concatenateModes(const std::vector<ModalModel>& parts) {
  MASTROM_REQUIRE(!parts.empty(), InputError, "modal model: nothing to concatenate");
  Eigen::Index k = 0;
  for (const ModalModel& p : parts) k += p.modeCount();
  ModalModel out = rigidWithRoomFor(parts.front(), k);
  Eigen::Index at = 0;
  for (const ModalModel& p : parts) {
    const Eigen::Index size = p.modeCount();
    out.omega_rad_s.segment(at, size) = p.omega_rad_s;
    out.damping_ratio.segment(at, size) = p.damping_ratio;
    out.rotation_participation.segment(at, size) = p.rotation_participation;
    out.centrifugal_participation.segment(at, size) = p.centrifugal_participation;
    out.end_rotation.middleCols(at, size) = p.end_rotation;
    out.end_translation.middleCols(at, size) = p.end_translation;
    out.momentum_participation.middleCols(at, size) = p.momentum_participation;
    at += size;
  }
  return out;
}

}  // namespace mastrom::rom
