// Joint drive laws (docs/theory.md §1; [LW24] eqs. 47–50 with the corrections stated there).
//
// Every law is written in the normalised time τ = t/T and returns θ, θ̇, θ̈ in closed form.
// Convention on [0, T]: the law's own formula is used for 0 ≤ t < T, so θ̈ is right-continuous where
// it jumps (trapezoidal breakpoints, cubic ends). Before t = 0 the joint is at rest at 0, from t =
// T on it is held at Θ.
#include "fullorder/drive_law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/drive_table.hpp"
#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

/// Polynomial laws θ = Θ p(τ): value, first and second τ-derivatives of p.
struct Normalised {
  double p, dp, ddp;
};

/// [LW24] eq. 49 corrected (docs/theory.md §1): p = 3τ² − 2τ³.
Normalised cubic(double tau) {
  return {tau * tau * (3.0 - 2.0 * tau), 6.0 * tau * (1.0 - tau), 6.0 - 12.0 * tau};
}

/// [LW24] eq. 49: p = 10τ³ − 15τ⁴ + 6τ⁵ (zero rate and acceleration at both ends, [LW24] eq. 48).
Normalised quintic(double tau) {
  const double t2 = tau * tau;
  return {t2 * tau * (10.0 + tau * (-15.0 + 6.0 * tau)),  //
          30.0 * t2 * (1.0 - tau) * (1.0 - tau),          // 30τ² − 60τ³ + 30τ⁴
          60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau)};  // 60τ − 180τ² + 120τ³
}

/// [LW24] eq. 50: p = τ − sin(2πτ)/(2π).
Normalised cycloidal(double tau) {
  const double phase = kTwoPi * tau;
  return {tau - std::sin(phase) / kTwoPi, 1.0 - std::cos(phase), kTwoPi * std::sin(phase)};
}

}  // namespace

DriveLaw::DriveLaw(const DriveLawParameters& params) : p_(params) {
  if (p_.kind == DriveLawKind::Table) {
    validateDriveTable(DriveTable{p_.table_time_s, p_.table_angle_rad}, "drive table");
    p_.duration_s = p_.table_time_s.back();
    p_.total_angle_rad = p_.table_angle_rad.back();
    // At rest at both ends: the spline's end slopes are zero (docs/theory.md (1.10)).
    table_ = ClampedCubicSpline(p_.table_time_s, p_.table_angle_rad, 0.0, 0.0);
  }
  const double angle = p_.total_angle_rad;
  const double duration = p_.duration_s;
  MASTROM_REQUIRE(std::isfinite(angle) && angle > 0.0, InputError,
                  "drive law: total_angle_rad = ", angle,
                  " is out of range (must be finite and > 0)");
  MASTROM_REQUIRE(std::isfinite(duration) && duration > 0.0, InputError,
                  "drive law: duration_s = ", duration,
                  " is out of range (must be finite and > 0)");
  if (p_.kind == DriveLawKind::Trapezoidal) {
    // Only the trapezoidal law reads t_r; the other laws ignore it, so it is not checked for them.
    const double ramp = p_.ramp_s;
    MASTROM_REQUIRE(std::isfinite(ramp) && ramp > 0.0 && ramp <= 0.5 * duration, InputError,
                    "drive law: ramp_s = ", ramp,
                    " is out of range (must satisfy 0 < ramp_s <= ", 0.5 * duration,
                    " = duration_s/2)");
    // Area under the trapezoid: ω (T − t_r) = Θ (docs/theory.md §1: 15 °/s for Θ = 90°, T = 6.1 s,
    // t_r =
    // 0.1 s).
    cruise_rate_rad_s_ = angle / (duration - ramp);
  }
}

/// θ̇ is a sum of terms of the size of the law's secant rates, each rounded; a few ulps of the
/// largest one is round-off, and 64 of them covers the tridiagonal solve of the table's spline
/// (docs/theory.md §1.5). A mast turning at that rate — ~10⁻¹⁴ rad/s for Θ = 90° in 6 s — is at
/// rest by any measure.
constexpr double kRestRoundoffUlps = 64.0;

double DriveLaw::restRateTolerance() const {
  double rate = p_.total_angle_rad / p_.duration_s;
  if (p_.kind == DriveLawKind::Table) {
    const std::vector<double>& t = p_.table_time_s;
    const std::vector<double>& a = p_.table_angle_rad;
    for (std::size_t i = 1; i < t.size(); ++i)
      rate = std::max(rate, std::abs(a[i] - a[i - 1]) / (t[i] - t[i - 1]));
  }
  return kRestRoundoffUlps * std::numeric_limits<double>::epsilon() * rate;
}

DriveLaw::Excitation DriveLaw::excitation() const {
  // Every law's θ̈ is piecewise smooth with few extrema per piece (a table's is linear between
  // rows, so its jerk is constant there): 4096 samples, the rows and the breakpoints find the
  // peaks to well within what a scale needs.
  constexpr int kSamples = 4096;
  const double duration = p_.duration_s;
  std::vector<double> t;
  for (int i = 0; i <= kSamples; ++i) t.push_back(duration * i / kSamples);
  for (double row : p_.table_time_s) t.push_back(row);
  const std::vector<double> stops = breakpoints();
  for (double b : stops) t.push_back(b);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  Excitation e;
  // θ̈ jumps at the start (from rest) and at every breakpoint (the end T among them).
  e.jump_rad_s2 = std::abs(at(0.0).acceleration_rad_s2);
  for (double b : stops) {
    const double left = at(b * (1.0 - 1e-12)).acceleration_rad_s2;
    const double right = at(b).acceleration_rad_s2;
    e.jump_rad_s2 = std::max(e.jump_rad_s2, std::abs(right - left));
  }
  DriveState previous = at(0.0);
  for (std::size_t i = 0; i < t.size(); ++i) {
    // The left limit at a breakpoint, so that no difference spans a jump.
    const bool is_stop = std::find(stops.begin(), stops.end(), t[i]) != stops.end();
    const DriveState d = at(is_stop ? t[i] * (1.0 - 1e-12) : t[i]);
    e.turn_rad_s2 = std::max(e.turn_rad_s2, std::hypot(d.acceleration_rad_s2,
                                                       d.rate_rad_s * d.rate_rad_s));
    if (i > 0)
      e.jerk_rad_s3 = std::max(e.jerk_rad_s3, std::abs(d.acceleration_rad_s2 -
                                                       previous.acceleration_rad_s2) /
                                                  (t[i] - t[i - 1]));
    previous = is_stop ? at(t[i]) : d;
  }
  return e;
}

bool DriveLaw::startsAtRest() const {
  return std::abs(at(0.0).rate_rad_s) <= restRateTolerance();
}

std::vector<double> DriveLaw::breakpoints() const {
  // Table: θ̈ jumps only at the ends; inside, the spline is C² and only θ⃛ steps at the rows, by
  // little where the data are smooth — as for the analytic laws, only T is declared.
  if (p_.kind == DriveLawKind::Trapezoidal) {
    // A ramp of exactly half the duration (no cruise: a triangular rate) has one jump in the
    // middle, from +a to −a, not two at the same instant.
    const double down = p_.duration_s - p_.ramp_s;
    if (down <= p_.ramp_s) return {p_.ramp_s, p_.duration_s};
    return {p_.ramp_s, down, p_.duration_s};
  }
  return {p_.duration_s};
}

DriveState DriveLaw::at(double time_s) const {
  MASTROM_REQUIRE(std::isfinite(time_s), InputError, "drive law: evaluated at non-finite time ",
                  time_s, " s");
  const double angle = p_.total_angle_rad;
  const double duration = p_.duration_s;
  if (time_s < 0.0) return {};
  if (time_s >= duration) return {angle, 0.0, 0.0};
  if (p_.kind == DriveLawKind::Table) {
    const ClampedCubicSpline::Value v = table_.at(time_s);
    return {v.y, v.dy, v.ddy};
  }

  if (p_.kind == DriveLawKind::Trapezoidal) {
    // [LW24] eq. 47: constant angular acceleration a = ω/t_r over [0, t_r), cruise at ω,
    // mirror-image ramp down over [T − t_r, T). Each piece is at most quadratic in t.
    const double ramp = p_.ramp_s;
    const double rate = cruise_rate_rad_s_;
    const double accel = rate / ramp;
    if (time_s < ramp) return {0.5 * accel * time_s * time_s, accel * time_s, accel};
    if (time_s < duration - ramp) return {rate * (time_s - 0.5 * ramp), rate, 0.0};
    const double remaining = duration - time_s;  // s = T − t ∈ (0, t_r]
    return {angle - 0.5 * accel * remaining * remaining, accel * remaining, -accel};
  }

  const double tau = time_s / duration;
  Normalised n{};
  switch (p_.kind) {
    case DriveLawKind::Cubic:
      n = cubic(tau);
      break;
    case DriveLawKind::Quintic:
      n = quintic(tau);
      break;
    case DriveLawKind::Cycloidal:
      n = cycloidal(tau);
      break;
    case DriveLawKind::Trapezoidal:
    case DriveLawKind::Table:
      break;  // handled above
  }
  // Chain rule: d/dt = (1/T) d/dτ.
  return {angle * n.p, angle * n.dp / duration, angle * n.ddp / (duration * duration)};
}

}  // namespace mastrom::fullorder
