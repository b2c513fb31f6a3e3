// The parabola polish of a sampled maximum: the vertex of the parabola through a largest sample and
// its two neighbours, and the error of that polish on a sinusoid (the method and its error bound:
// the header comment of rom/model/deployment_metrics.hpp, and docs/theory.md §6.5). Not part of
// the library's interface.
#pragma once

#include <algorithm>
#include <cmath>

namespace mastrom::rom {

/// The polish's error on a sinusoid sampled at phase steps x = ωh, relative to its amplitude:
/// e(x) = 0.0234 x⁴, at most 2 (the samples may miss the peak entirely).
inline double polishError(double x) { return std::min(2.0, 0.0234 * x * x * x * x); }

/// The vertex of the parabola through (−1, v_minus), (0, v0), (1, v_plus) when it is a maximum
/// within [−1, 1]: its value and abscissa; false otherwise.
inline bool parabolaMaximum(double v_minus, double v0, double v_plus, double& value,
                            double& offset) {
  const double curvature = v_plus + v_minus - 2.0 * v0, slope = 0.5 * (v_plus - v_minus);
  if (!(curvature < 0.0)) return false;
  offset = -slope / curvature;
  if (std::abs(offset) > 1.0) return false;
  value = v0 - 0.5 * slope * slope / curvature;
  return true;
}

}  // namespace mastrom::rom
