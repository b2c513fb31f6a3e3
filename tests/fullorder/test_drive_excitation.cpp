// What a drive asks of the mast, known before the first step (docs/theory.md §5.3a): the drive's
// peaks against their closed forms, and the held mast's quasi-static compliance to a unit drive
// acceleration against the exact scaling of linear elasticity.
#include <cmath>

#include <gtest/gtest.h>

#include "coarse_mast.hpp"
#include "fullorder/drive_compliance.hpp"
#include "fullorder/drive_law.hpp"
#include "fullorder/mast_config.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(DriveExcitation, CycloidalPeaksAreTheClosedForms) {
  DriveLawParameters p;
  p.kind = DriveLawKind::Cycloidal;
  p.total_angle_rad = kPi / 2;
  p.duration_s = 6.1;
  const DriveLaw law(p);
  const DriveLaw::Excitation e = law.excitation();
  // θ⃛ = Θ (2π)² / T³ cos(2πt/T): largest at the ends; θ̈ starts and ends at 0: no jump.
  const double jerk = p.total_angle_rad * 4 * kPi * kPi / std::pow(p.duration_s, 3);
  EXPECT_NEAR(e.jerk_rad_s3, jerk, 1e-5 * jerk);
  EXPECT_LT(e.jump_rad_s2, 1e-9 * jerk * p.duration_s);
  // √(θ̈² + θ̇⁴) on a grid 250 times finer than the function's own.
  double turn = 0.0;
  for (int i = 0; i <= 1000000; ++i) {
    const DriveState d = law.at(p.duration_s * i / 1000000);
    turn = std::max(turn, std::hypot(d.acceleration_rad_s2, d.rate_rad_s * d.rate_rad_s));
  }
  EXPECT_NEAR(e.turn_rad_s2, turn, 1e-5 * turn);
}

TEST(DriveExcitation, TrapezoidalJumpsAndNoJerkInsideItsPieces) {
  DriveLawParameters p;  // the paper's: 90° in 6.1 s, ramps of 0.1 s
  const DriveLaw law(p);
  const DriveLaw::Excitation e = law.excitation();
  const double accel = p.total_angle_rad / (p.duration_s - p.ramp_s) / p.ramp_s;
  EXPECT_NEAR(e.jump_rad_s2, accel, 1e-12 * accel);  // 0 → a at the start, a → 0 at t_r, …
  EXPECT_LT(e.jerk_rad_s3, 1e-6 * accel);             // no difference spans a jump
  const double rate = accel * p.ramp_s;
  EXPECT_NEAR(e.turn_rad_s2, std::hypot(accel, rate * rate), 1e-9 * accel);
}

TEST(DriveCompliance, ScalesExactlyWithTheModulus) {
  // Linear elasticity: the deflection under a given load is ∝ 1/E and the Rayleigh frequency
  // ∝ √E.
  Config c = testing::coarseScheme1();
  c.mast.modules = 3;
  const DriveCompliance soft = driveCompliance(buildMast(mastParametersFromConfig(c)));
  c.material.youngs_modulus_pa *= 4.0;
  const DriveCompliance stiff = driveCompliance(buildMast(mastParametersFromConfig(c)));
  ASSERT_GT(soft.module_deflection_m_per_rad_s2, 0.0);
  ASSERT_GT(soft.rayleigh_frequency_rad_s, 0.0);
  EXPECT_NEAR(stiff.module_deflection_m_per_rad_s2, soft.module_deflection_m_per_rad_s2 / 4,
              1e-8 * soft.module_deflection_m_per_rad_s2);
  EXPECT_NEAR(stiff.rayleigh_frequency_rad_s, 2 * soft.rayleigh_frequency_rad_s,
              1e-8 * soft.rayleigh_frequency_rad_s);
  // Size: the tip of a 0.3 m mast on 2 mm aluminium rings bends by ~10⁻⁷ m per rad/s² (the
  // end's rigid acceleration ρ θ̈ over ω² ≈ 0.3 / 2000²).
  EXPECT_GT(soft.module_deflection_m_per_rad_s2, 1e-9);
  EXPECT_LT(soft.module_deflection_m_per_rad_s2, 1e-5);
}

}  // namespace
}  // namespace mastrom::fullorder
