#include "rom/model/modulus_scaling.hpp"

#include <cmath>

#include "common/error.hpp"

namespace mastrom::rom {

void scaleYoungsModulus(ModalModel& model, double ratio) {
  MASTROM_REQUIRE(std::isfinite(ratio) && ratio > 0.0, InputError,
                  "rom: the ratio of Young's moduli E/E0 = ", ratio, " must be finite and > 0");
  MASTROM_REQUIRE(model.gravity_m_s2.isZero(0.0), InputError,
                  "rom: the modes scale exactly with Young's modulus only without gravity (the "
                  "preload's geometric stiffness does not scale with E)");
  const double root = std::sqrt(ratio);
  model.omega_rad_s *= root;
  model.damping_ratio *= root;
  if (!model.stress.empty()) model.stress.modes *= ratio;
}

}  // namespace mastrom::rom
