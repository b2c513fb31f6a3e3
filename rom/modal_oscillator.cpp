#include "rom/modal_oscillator.hpp"

#include <cmath>

#include <unsupported/Eigen/MatrixFunctions>

#include "common/error.hpp"

namespace mastrom::rom {

OscillatorStep discretizeOscillator(double omega_rad_s, double zeta, double step_s) {
  MASTROM_REQUIRE(std::isfinite(omega_rad_s) && omega_rad_s >= 0.0, InputError,
                  "modal oscillator: omega = ", omega_rad_s, " rad/s must be finite and >= 0");
  MASTROM_REQUIRE(std::isfinite(zeta) && zeta >= 0.0, InputError, "modal oscillator: zeta = ", zeta,
                  " must be finite and >= 0");
  MASTROM_REQUIRE(std::isfinite(step_s) && step_s > 0.0, InputError, "modal oscillator: step = ",
                  step_s, " s must be > 0");
  Eigen::Matrix4d aug = Eigen::Matrix4d::Zero();
  aug(0, 1) = 1.0;
  aug(1, 0) = -omega_rad_s * omega_rad_s;
  aug(1, 1) = -2.0 * zeta * omega_rad_s;
  aug(1, 2) = 1.0;  // g = [0; 1] multiplies f
  aug(2, 3) = 1.0;  // ḟ drives f
  const Eigen::Matrix4d e = (aug * step_s).exp();
  OscillatorStep s;
  s.a = e.topLeftCorner<2, 2>();
  const Eigen::Vector2d gamma0 = e.block<2, 1>(0, 2);
  const Eigen::Vector2d gamma1 = e.block<2, 1>(0, 3);  // Γ₁ (the ḟ column)
  s.b1 = gamma1 / step_s;
  s.b0 = gamma0 - s.b1;
  return s;
}

}  // namespace mastrom::rom
