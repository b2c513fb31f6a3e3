// Exact discrete-time oscillator (docs/theory.md §4.1) against closed-form responses.
#include <cmath>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "rom/model/modal_oscillator.hpp"

namespace mastrom::rom {
namespace {

TEST(ModalOscillator, FreeDecayMatchesClosedForm) {
  const double w = 2 * M_PI * 120.0, z = 0.02, dt = 1e-3;
  const OscillatorStep s = discretizeOscillator(w, z, dt);
  const double wd = w * std::sqrt(1 - z * z);
  Eigen::Vector2d x(1e-3, 0.0);
  for (int k = 1; k <= 500; ++k) {
    x = advance(s, x, 0.0, 0.0);
    const double t = k * dt;
    // η(t) = η₀ e^{−ζωt}(cos ω_d t + ζω/ω_d sin ω_d t) for η̇₀ = 0.
    const double exact = 1e-3 * std::exp(-z * w * t) * (std::cos(wd * t) + z * w / wd * std::sin(wd * t));
    // Round-off of the Padé exponential (~1e-15 relative) accumulates over 500 steps.
    ASSERT_NEAR(x[0], exact, 1e-12 * 1e-3) << "step " << k;
  }
}

TEST(ModalOscillator, RampForcingIsExactForAnyStep) {
  // f(t) = c t from rest: η = c/ω² (t − 2ζ/ω) + transient; compare with the closed form for ζ = 0:
  // η = c/ω² (t − sin(ωt)/ω). First-order hold is exact for linear forcing, whatever Δ.
  const double w = 40.0, c = 3.0;
  for (double dt : {1e-3, 0.05, 0.3}) {
    const OscillatorStep s = discretizeOscillator(w, 0.0, dt);
    Eigen::Vector2d x(0.0, 0.0);
    for (int k = 0; k < 20; ++k) x = advance(s, x, c * k * dt, c * (k + 1) * dt);
    const double t = 20 * dt;
    EXPECT_NEAR(x[0], c / (w * w) * (t - std::sin(w * t) / w), 1e-13 * (1 + c * t / (w * w)));
    EXPECT_NEAR(x[1], c / (w * w) * (1 - std::cos(w * t)), 1e-13);
  }
}

TEST(ModalOscillator, RigidModeIntegratesTwice) {
  // ω = 0: η̈ = f. Constant f for one step: η = ½ f Δ², η̇ = f Δ.
  const OscillatorStep s = discretizeOscillator(0.0, 0.0, 0.1);
  const Eigen::Vector2d x = advance(s, Eigen::Vector2d(0.5, 1.0), 2.0, 2.0);
  EXPECT_NEAR(x[0], 0.5 + 0.1 + 0.5 * 2.0 * 0.01, 1e-15);
  EXPECT_NEAR(x[1], 1.0 + 0.2, 1e-15);
}

TEST(ModalOscillator, OverdampedStepResponseSettlesToStaticValue) {
  const double w = 10.0;
  const OscillatorStep s = discretizeOscillator(w, 3.0, 0.01);
  Eigen::Vector2d x(0.0, 0.0);
  for (int k = 0; k < 20000; ++k) x = advance(s, x, 5.0, 5.0);
  EXPECT_NEAR(x[0], 5.0 / (w * w), 1e-12);
}

TEST(ModalOscillator, RejectsBadInput) {
  EXPECT_THROW(discretizeOscillator(-1.0, 0.0, 0.1), InputError);
  EXPECT_THROW(discretizeOscillator(1.0, -0.1, 0.1), InputError);
  EXPECT_THROW(discretizeOscillator(1.0, 0.0, 0.0), InputError);
  EXPECT_THROW(discretizeOscillator(std::nan(""), 0.0, 0.1), InputError);
}

}  // namespace
}  // namespace mastrom::rom
