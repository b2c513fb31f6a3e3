// Clamped cubic spline (see the header): the knots' second derivatives M_i from the tridiagonal
// continuity equations of y' (docs/theory.md (1.10)), solved by the Thomas algorithm (diagonally
// dominant, so no pivoting is needed).
#include "fullorder/cubic_spline.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::fullorder {

ClampedCubicSpline::ClampedCubicSpline(std::vector<double> t, std::vector<double> y,
                                       double slope_start, double slope_end)
    : t_(std::move(t)), y_(std::move(y)), slope_start_(slope_start), slope_end_(slope_end) {
  const std::size_t n = t_.size();
  MASTROM_REQUIRE(n >= 2 && y_.size() == n, InputError, "cubic spline: ", n, " knots and ",
                  y_.size(), " values (need equal counts, at least 2)");
  for (std::size_t i = 1; i < n; ++i)
    MASTROM_REQUIRE(t_[i] > t_[i - 1], InputError, "cubic spline: knot ", i, " at ", t_[i],
                    " does not exceed the previous one at ", t_[i - 1]);
  // Row i: a_i M_{i−1} + b_i M_i + c_i M_{i+1} = r_i.
  std::vector<double> a(n, 0.0), b(n, 0.0), c(n, 0.0), r(n, 0.0);
  const auto h = [this](std::size_t i) { return t_[i + 1] - t_[i]; };
  const auto slope = [this, &h](std::size_t i) { return (y_[i + 1] - y_[i]) / h(i); };
  b[0] = 2.0 * h(0);
  c[0] = h(0);
  r[0] = 6.0 * (slope(0) - slope_start);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    a[i] = h(i - 1);
    b[i] = 2.0 * (h(i - 1) + h(i));
    c[i] = h(i);
    r[i] = 6.0 * (slope(i) - slope(i - 1));
  }
  a[n - 1] = h(n - 2);
  b[n - 1] = 2.0 * h(n - 2);
  r[n - 1] = 6.0 * (slope_end - slope(n - 2));
  for (std::size_t i = 1; i < n; ++i) {  // forward elimination
    const double w = a[i] / b[i - 1];
    b[i] -= w * c[i - 1];
    r[i] -= w * r[i - 1];
  }
  second_.assign(n, 0.0);
  second_[n - 1] = r[n - 1] / b[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) second_[i] = (r[i] - c[i] * second_[i + 1]) / b[i];
}

ClampedCubicSpline::Value ClampedCubicSpline::at(double t) const {
  const auto it = std::upper_bound(t_.begin(), t_.end(), t);
  const std::size_t i = std::min<std::size_t>(
      static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - t_.begin() - 1, 0)), t_.size() - 2);
  const double h = t_[i + 1] - t_[i];
  const double a = t_[i + 1] - t, bb = t - t_[i];
  const double m0 = second_[i], m1 = second_[i + 1];
  const double c0 = y_[i] / h - m0 * h / 6.0, c1 = y_[i + 1] / h - m1 * h / 6.0;
  Value v;
  v.y = (m0 * a * a * a + m1 * bb * bb * bb) / (6.0 * h) + c0 * a + c1 * bb;
  v.dy = (m1 * bb * bb - m0 * a * a) / (2.0 * h) - c0 + c1;
  v.ddy = (m0 * a + m1 * bb) / h;
  if (t == t_.front()) v.dy = slope_start_;
  if (t == t_.back()) v.dy = slope_end_;
  return v;
}

}  // namespace mastrom::fullorder
