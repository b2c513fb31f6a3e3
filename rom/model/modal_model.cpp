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

}  // namespace mastrom::rom
