// The clamped C² cubic spline through (t_i, y_i) with given end slopes: the interpolant of a
// tabulated drive profile (docs/theory.md §1.5, (1.9)). Among all C² interpolants it minimises
// ∫ (y'')² dt (de Boor, "A Practical Guide to Splines", 2001, ch. IV), so θ, θ̇ and θ̈ are
// continuous and θ̈ does not oscillate between the rows; it reproduces every cubic polynomial whose
// end slopes it is given exactly, with error O(h⁴) in θ and O(h²) in θ̈ for smooth data.
#pragma once

#include <vector>

namespace mastrom::fullorder {

class ClampedCubicSpline {
public:
  struct Value {
    double y = 0.0, dy = 0.0, ddy = 0.0;  ///< y(t), y'(t), y''(t)
  };

  ClampedCubicSpline() = default;
  /// Knots t (strictly increasing, ≥ 2), values y, end slopes. Throws InputError on bad sizes or
  /// knots that do not increase.
  ClampedCubicSpline(std::vector<double> t, std::vector<double> y, double slope_start,
                     double slope_end);

  /// The spline at t ∈ [t_0, t_n] (outside: the end piece's cubic). At the end knots y' is the
  /// slope it was clamped to, exactly, not that slope plus the round-off of the formula (a start
  /// from rest must read as one: docs/theory.md §1.5).
  Value at(double t) const;
  const std::vector<double>& knots() const { return t_; }
  const std::vector<double>& values() const { return y_; }

private:
  std::vector<double> t_, y_;
  std::vector<double> second_;  ///< y'' at the knots
  double slope_start_ = 0.0, slope_end_ = 0.0;
};

}  // namespace mastrom::fullorder
