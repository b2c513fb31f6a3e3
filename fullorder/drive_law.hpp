// Joint drive laws θ(t) from 0 to Θ over a duration T, held at Θ afterwards
// (docs/theory.md §1 "Drive laws"; [LW24] eqs. 47–50 with the corrections stated there).
// Every law returns θ, θ̇, θ̈ analytically; the tabulated law ("table": a measured profile) through a
// clamped C² cubic spline (fullorder/cubic_spline.hpp, docs/theory.md §1.5), whose last row gives
// T and Θ.
#pragma once

#include <vector>

#include "common/kinds.hpp"
#include "fullorder/cubic_spline.hpp"

namespace mastrom::fullorder {

/// Drive state at one instant: angle [rad], rate [rad/s], acceleration [rad/s²].
struct DriveState {
  double angle_rad = 0.0;
  double rate_rad_s = 0.0;
  double acceleration_rad_s2 = 0.0;
};

struct DriveLawParameters {
  DriveLawKind kind = DriveLawKind::Trapezoidal;
  double total_angle_rad = 1.5707963267948966;  ///< Θ
  double duration_s = 6.1;                       ///< T
  double ramp_s = 0.1;                           ///< t_r (trapezoidal only)
  /// Table law: the rows (time from 0, angle from 0; common/drive_table.hpp checks them). T and Θ
  /// are then the last row's, whatever duration_s and total_angle_rad say.
  std::vector<double> table_time_s;
  std::vector<double> table_angle_rad;
};

class DriveLaw {
public:
  explicit DriveLaw(const DriveLawParameters& params);  ///< throws InputError on bad parameters
  DriveState at(double time_s) const;
  const DriveLawParameters& parameters() const { return p_; }
  /// Instants in (0, T] where θ̈ or its derivative jumps (trapezoidal: t_r, T − t_r, T — t_r and T
  /// when t_r = T/2; the others: T), strictly ascending. Exact integrators (the ROM) split their
  /// steps there.
  std::vector<double> breakpoints() const;
  /// What the drive asks of the mast, for the step control's scales (docs/theory.md §5.3a), on a
  /// fine sampling of [0, T] with the table's rows and the breakpoints' left limits:
  struct Excitation {
    double turn_rad_s2 = 0.0;        ///< max √(θ̈² + θ̇⁴): a point at radius ρ turns at ρ times it
    double jerk_rad_s3 = 0.0;        ///< max |θ⃛| inside the smooth pieces
    double jump_rad_s2 = 0.0;        ///< the largest jump of θ̈ (at 0, a breakpoint or T)
  };
  Excitation excitation() const;
  /// Whether the joint is at rest at t = 0 (docs/theory.md §1.5): |θ̇(0)| within
  /// restRateTolerance(). Every law is at rest there in exact arithmetic (the table's spline by its
  /// clamped end slope); this says so also when θ̇(0) is the round-off of an evaluation.
  bool startsAtRest() const;
  /// The rate [rad/s] below which θ̇ is round-off: kRestRoundoffUlps ε times the law's largest
  /// mean rate (for a table, its largest secant rate Δθ/Δt between rows).
  double restRateTolerance() const;

private:
  DriveLawParameters p_;
  double cruise_rate_rad_s_ = 0.0;  ///< trapezoidal: Θ / (T − t_r)
  ClampedCubicSpline table_;        ///< table law: θ(t), at rest at both ends
};

}  // namespace mastrom::fullorder
