// Tests of the joint drive laws (docs/theory.md §1; [LW24] eqs. 47–50).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "fullorder/drive_law.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr std::array<DriveLawKind, 4> kAllKinds{DriveLawKind::Trapezoidal, DriveLawKind::Cubic,
                                                DriveLawKind::Quintic, DriveLawKind::Cycloidal};

DriveLaw makeLaw(DriveLawKind kind) {
  DriveLawParameters p;
  p.kind = kind;
  return DriveLaw(p);
}

/// Bounds on |dᵏp/dτᵏ| over τ ∈ [0, 1] for θ = Θ p(t/T), k = 0 … 4, worked out by hand from the
/// closed forms. Trapezoidal: θ is piecewise quadratic, so within a piece the third and fourth
/// derivatives vanish; its bounds for p, p′, p″ use ω = Θ/(T − t_r) and a = ω/t_r.
std::array<double, 5> normalisedDerivativeBounds(const DriveLaw& law) {
  const DriveLawParameters& p = law.parameters();
  switch (p.kind) {
    case DriveLawKind::Cubic:  // p = 3τ² − 2τ³: p′ ≤ 3/2, p″ = 6 − 12τ, p‴ = −12
      return {1.0, 1.5, 6.0, 12.0, 0.0};
    case DriveLawKind::Quintic:  // p′ = 30τ²(1−τ)² ≤ 15/8; |p″| ≤ 10/√3; p‴ ≤ 60; p⁗ = 720τ − 360
      return {1.0, 1.875, 5.78, 60.0, 360.0};
    case DriveLawKind::Cycloidal:  // p′ = 1 − cos 2πτ, p″ = 2π sin, p‴ = 4π² cos, p⁗ = −8π³ sin
      return {1.0, 2.0, 2.0 * kPi, 4.0 * kPi * kPi, 8.0 * kPi * kPi * kPi};
    case DriveLawKind::Trapezoidal: {
      const double rate_over = p.duration_s / (p.duration_s - p.ramp_s);  // ω T / Θ
      return {1.0, rate_over, rate_over * p.duration_s / p.ramp_s, 0.0, 0.0};
    }
    case DriveLawKind::Table:  // not an analytic law: tests/fullorder/test_real_mast.cpp
      break;
  }
  return {};
}

/// Central difference of f at t with step h. The two abscissae are exact doubles and the divisor is
/// their computed difference, so the representation error of t ± h does not enter.
template <typename F>
double centralDifference(const F& f, double t, double h) {
  const double tp = t + h;
  const double tm = t - h;
  return (f(tp) - f(tm)) / (tp - tm);
}

// ---------------------------------------------------------------------------------------------
TEST(DriveLaw, BoundaryConditionsOfP48) {
  for (DriveLawKind kind : kAllKinds) {
    SCOPED_TRACE(toString(kind));
    const DriveLaw law = makeLaw(kind);
    const double angle = law.parameters().total_angle_rad;
    const double duration = law.parameters().duration_s;
    const DriveState start = law.at(0.0);
    EXPECT_EQ(start.angle_rad, 0.0);
    EXPECT_EQ(start.rate_rad_s, 0.0);
    // Just before the end the formula itself (not the hold branch) must meet θ = Θ, θ̇ = 0.
    const double t_end = duration * (1.0 - 1e-12);
    const DriveState before_end = law.at(t_end);
    EXPECT_NEAR(before_end.angle_rad, angle, 1e-12 * angle);
    EXPECT_NEAR(before_end.rate_rad_s, 0.0, 1e-10 * angle / duration);
    const DriveState end = law.at(duration);
    EXPECT_EQ(end.angle_rad, angle);
    EXPECT_EQ(end.rate_rad_s, 0.0);
    EXPECT_EQ(end.acceleration_rad_s2, 0.0);
    if (kind == DriveLawKind::Quintic || kind == DriveLawKind::Cycloidal) {
      // [LW24] eq. 48 quintic (and the cycloid by construction): zero acceleration at both ends.
      EXPECT_NEAR(start.acceleration_rad_s2, 0.0, 1e-14 * angle / (duration * duration));
      EXPECT_NEAR(before_end.acceleration_rad_s2, 0.0, 1e-9 * angle / (duration * duration));
    }
  }
}

TEST(DriveLaw, AtRestBeforeStartAndHeldAfterEnd) {
  for (DriveLawKind kind : kAllKinds) {
    SCOPED_TRACE(toString(kind));
    const DriveLaw law = makeLaw(kind);
    const double angle = law.parameters().total_angle_rad;
    for (double t : {-1e3, -1.0, -1e-12}) {
      const DriveState s = law.at(t);
      EXPECT_EQ(s.angle_rad, 0.0);
      EXPECT_EQ(s.rate_rad_s, 0.0);
      EXPECT_EQ(s.acceleration_rad_s2, 0.0);
    }
    for (double t : {6.1, 6.1 + 1e-12, 7.0, 1e3}) {
      const DriveState s = law.at(t);
      EXPECT_EQ(s.angle_rad, angle);
      EXPECT_EQ(s.rate_rad_s, 0.0);
      EXPECT_EQ(s.acceleration_rad_s2, 0.0);
    }
  }
}

TEST(DriveLaw, PointSymmetricAboutMidTime) {
  // All four laws satisfy θ(T − t) = Θ − θ(t), θ̇(T − t) = θ̇(t), θ̈(T − t) = −θ̈(t).
  for (DriveLawKind kind : kAllKinds) {
    SCOPED_TRACE(toString(kind));
    const DriveLaw law = makeLaw(kind);
    const double angle = law.parameters().total_angle_rad;
    const double duration = law.parameters().duration_s;
    const std::array<double, 5> b = normalisedDerivativeBounds(law);
    for (double t : {0.03, 0.37, 1.0, 2.2, 3.0}) {
      const DriveState a = law.at(t);
      const DriveState m = law.at(duration - t);
      EXPECT_NEAR(m.angle_rad, angle - a.angle_rad, 1e-14 * angle);
      EXPECT_NEAR(m.rate_rad_s, a.rate_rad_s, 1e-12 * b[1] * angle / duration);
      EXPECT_NEAR(m.acceleration_rad_s2, -a.acceleration_rad_s2,
                  1e-12 * b[2] * angle / (duration * duration));
    }
  }
}

TEST(DriveLaw, TrapezoidalDefaultsMatchP47) {
  const DriveLaw law = makeLaw(DriveLawKind::Trapezoidal);
  // Cruise ω = Θ/(T − t_r) = 90°/6 s = 15 °/s; ramp acceleration 150 °/s² ([LW24] eq. 47: ω = 150
  // t).
  EXPECT_NEAR(law.at(3.0).rate_rad_s, 15.0 * kDeg, 1e-14);
  EXPECT_EQ(law.at(3.0).acceleration_rad_s2, 0.0);
  EXPECT_NEAR(law.at(0.05).rate_rad_s, 150.0 * kDeg * 0.05, 1e-14);
  EXPECT_NEAR(law.at(0.05).acceleration_rad_s2, 150.0 * kDeg, 1e-12);
  EXPECT_NEAR(law.at(6.05).acceleration_rad_s2, -150.0 * kDeg, 1e-12);
  // [LW24] eq. 47 ramp down: ω = −150 t + 915 (°/s) on [6, 6.1].
  EXPECT_NEAR(law.at(6.07).rate_rad_s, (-150.0 * 6.07 + 915.0) * kDeg, 1e-12);
  EXPECT_NEAR(law.at(6.1).angle_rad, 90.0 * kDeg, 1e-15);
  EXPECT_NEAR(law.at(std::nextafter(6.1, 0.0)).angle_rad, 90.0 * kDeg, 1e-14);
  // Breakpoint angles in closed form: ½ω t_r after the ramp up, Θ − ½ω t_r before the ramp down.
  const double omega = 15.0 * kDeg;
  EXPECT_NEAR(law.at(0.1).angle_rad, 0.5 * omega * 0.1, 1e-15);
  EXPECT_NEAR(law.at(6.0).angle_rad, 90.0 * kDeg - 0.5 * omega * 0.1, 1e-14);
}

TEST(DriveLaw, TrapezoidalWithoutCruiseIsTriangular) {
  DriveLawParameters p;
  p.duration_s = 2.0;
  p.ramp_s = 1.0;  // t_r = T/2, the largest allowed
  const DriveLaw law(p);
  EXPECT_NEAR(law.at(1.0).rate_rad_s, 2.0 * p.total_angle_rad / p.duration_s, 1e-15);
  EXPECT_NEAR(law.at(1.0).angle_rad, 0.5 * p.total_angle_rad, 1e-15);
  EXPECT_NEAR(law.at(std::nextafter(2.0, 0.0)).angle_rad, p.total_angle_rad, 1e-15);
  // One jump of θ̈ in the middle (+a to −a), declared once: a step control that lands on every
  // breakpoint in turn would otherwise be asked for a step of length zero.
  EXPECT_EQ(law.breakpoints(), (std::vector<double>{1.0, 2.0}));
  EXPECT_GT(law.at(std::nextafter(1.0, 0.0)).acceleration_rad_s2, 0.0);
  EXPECT_LT(law.at(1.0).acceleration_rad_s2, 0.0);
  p.ramp_s = 0.5;
  EXPECT_EQ(DriveLaw(p).breakpoints(), (std::vector<double>{0.5, 1.5, 2.0}));
}

// Central-difference check of θ̇ = dθ/dt and θ̈ = dθ̇/dt at interior points.
// Error of the central difference of f with step h (Taylor + rounding):
//   |D_h f − f′| ≤ h²/6 · max|f‴| + e_f / h,
// where e_f bounds the rounding error of one evaluation of f. Each law is a handful of flops on
// τ = t/T, and the relative error ε of τ propagates as ε·T·|f′|, so e_f = 8ε(max|f| + T max|f′|).
// The step h = ∛ε·T balances the two terms up to the O(1) derivative bounds; the tolerance is the
// bound itself with a factor 2 of safety. At the default T = 6.1 s this is ~3e-10 relative to the
// derivative's scale: a wrong coefficient in any formula shows up at O(1).
TEST(DriveLaw, DerivativesMatchCentralDifferences) {
  for (DriveLawKind kind : kAllKinds) {
    SCOPED_TRACE(toString(kind));
    const DriveLaw law = makeLaw(kind);
    const DriveLawParameters& p = law.parameters();
    const double angle = p.total_angle_rad;
    const double duration = p.duration_s;
    const std::array<double, 5> b = normalisedDerivativeBounds(law);
    // Dimensional bounds: max|θ⁽ᵏ⁾| ≤ Θ b_k / Tᵏ.
    std::array<double, 5> bound{};
    for (std::size_t k = 0; k < bound.size(); ++k)
      bound[k] = angle * b[k] / std::pow(duration, static_cast<double>(k));

    const double h = std::cbrt(kEps) * duration;
    const double rate_tol =
        2.0 * (h * h / 6.0 * bound[3] + 8.0 * kEps * (bound[0] + duration * bound[1]) / h);
    const double accel_tol =
        2.0 * (h * h / 6.0 * bound[4] + 8.0 * kEps * (bound[1] + duration * bound[2]) / h);
    // The trapezoid has breakpoints where θ̈ jumps: keep the stencil clear of them there.
    const std::vector<double> breakpoints{0.0, p.ramp_s, duration - p.ramp_s, duration};

    const auto angle_at = [&](double t) { return law.at(t).angle_rad; };
    const auto rate_at = [&](double t) { return law.at(t).rate_rad_s; };
    int checked = 0;
    constexpr int kSamples = 200;
    for (int i = 0; i < kSamples; ++i) {
      const double t = duration * (i + 0.5) / kSamples;  // includes points inside both ramps
      bool near_break = false;
      for (double bp : breakpoints) near_break = near_break || std::abs(t - bp) < 2.0 * h;
      if (kind == DriveLawKind::Trapezoidal && near_break) continue;
      const DriveState s = law.at(t);
      EXPECT_NEAR(s.rate_rad_s, centralDifference(angle_at, t, h), rate_tol) << "t = " << t;
      EXPECT_NEAR(s.acceleration_rad_s2, centralDifference(rate_at, t, h), accel_tol)
          << "t = " << t;
      ++checked;
    }
    EXPECT_GE(checked, kSamples - 4);
  }
}

TEST(DriveLaw, TrapezoidalContinuityAcrossBreakpoints) {
  const DriveLaw law = makeLaw(DriveLawKind::Trapezoidal);
  const DriveLawParameters& p = law.parameters();
  const double rate = p.total_angle_rad / (p.duration_s - p.ramp_s);
  const double accel = rate / p.ramp_s;
  // θ is C¹: across a breakpoint b, |θ(b+δ) − θ(b−δ)| ≤ 2δ·max|θ̇| and
  // |θ̇(b+δ) − θ̇(b−δ)| ≤ 2δ·max|θ̈|; θ̈ jumps by the ramp acceleration.
  struct Break {
    double time_s;
    double accel_before, accel_after;
  };
  const std::array<Break, 4> breaks{{{0.0, 0.0, accel},
                                     {p.ramp_s, accel, 0.0},
                                     {p.duration_s - p.ramp_s, 0.0, -accel},
                                     {p.duration_s, -accel, 0.0}}};
  const double delta = 1e-9;
  for (const Break& b : breaks) {
    SCOPED_TRACE("breakpoint t = " + std::to_string(b.time_s));
    const DriveState before = law.at(b.time_s - delta);
    const DriveState after = law.at(b.time_s + delta);
    const DriveState at = law.at(b.time_s);
    EXPECT_NEAR(after.angle_rad, before.angle_rad, 2.0 * delta * rate + 1e-15);
    EXPECT_NEAR(after.rate_rad_s, before.rate_rad_s, 2.0 * delta * accel + 1e-15);
    EXPECT_NEAR(at.angle_rad, before.angle_rad, delta * rate + 1e-15);
    EXPECT_NEAR(at.rate_rad_s, before.rate_rad_s, delta * accel + 1e-15);
    EXPECT_NEAR(before.acceleration_rad_s2, b.accel_before, 1e-12);
    EXPECT_NEAR(after.acceleration_rad_s2, b.accel_after, 1e-12);
    // θ̈ is right-continuous: the value at the breakpoint is the one after it.
    EXPECT_NEAR(at.acceleration_rad_s2, b.accel_after, 1e-12);
  }
}

TEST(DriveLaw, SmoothLawsAreContinuousAtStartAndEnd) {
  // Cubic: θ, θ̇ continuous at 0 and T; quintic and cycloidal also θ̈.
  const double delta = 1e-9;
  for (DriveLawKind kind : {DriveLawKind::Cubic, DriveLawKind::Quintic, DriveLawKind::Cycloidal}) {
    SCOPED_TRACE(toString(kind));
    const DriveLaw law = makeLaw(kind);
    const std::array<double, 5> b = normalisedDerivativeBounds(law);
    const double angle = law.parameters().total_angle_rad;
    const double duration = law.parameters().duration_s;
    for (double t : {0.0, duration}) {
      const DriveState before = law.at(t - delta);
      const DriveState after = law.at(t + delta);
      EXPECT_NEAR(after.angle_rad, before.angle_rad, 2.0 * delta * b[1] * angle / duration + 1e-15);
      EXPECT_NEAR(after.rate_rad_s, before.rate_rad_s,
                  2.0 * delta * b[2] * angle / (duration * duration) + 1e-15);
      if (kind != DriveLawKind::Cubic) {
        EXPECT_NEAR(after.acceleration_rad_s2, before.acceleration_rad_s2,
                    2.0 * delta * b[3] * angle / std::pow(duration, 3.0) + 1e-14);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
/// Expect construction to throw InputError whose message names `key`.
void expectRejected(const DriveLawParameters& p, const std::string& key) {
  try {
    const DriveLaw law(p);
    static_cast<void>(law);
    ADD_FAILURE() << "accepted " << key;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(DriveLaw, RejectsBadParameters) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (DriveLawKind kind : kAllKinds) {
    SCOPED_TRACE(toString(kind));
    DriveLawParameters base;
    base.kind = kind;
    for (double bad : {0.0, -1.0, nan, inf}) {
      DriveLawParameters p = base;
      p.total_angle_rad = bad;
      expectRejected(p, "total_angle_rad");
      p = base;
      p.duration_s = bad;
      expectRejected(p, "duration_s");
    }
  }
  DriveLawParameters base;
  base.kind = DriveLawKind::Trapezoidal;
  for (double bad : {0.0, -0.1, std::nextafter(3.05, 4.0), 6.1, nan, inf}) {
    DriveLawParameters p = base;
    p.ramp_s = bad;
    expectRejected(p, "ramp_s");
  }
  // The other laws do not read t_r, so it is not held against them.
  DriveLawParameters cubic;
  cubic.kind = DriveLawKind::Cubic;
  cubic.ramp_s = 100.0;
  EXPECT_NO_THROW(DriveLaw{cubic});

  const DriveLaw law(base);
  EXPECT_THROW(law.at(nan), InputError);
}

}  // namespace
}  // namespace mastrom::fullorder
