// The parabola polish of a sampled maximum: the vertex of the parabola through a largest sample and
// its two neighbours, and the error of that polish on a sinusoid. One definition for the ROM's
// continuous peaks (peak_refinement.hpp) and its stress peaks (modal_stress_response.hpp); the
// method and its error bound are the header comment of rom/model/deployment_metrics.hpp and
// docs/theory.md §6.5. Not part of the library's interface.
#pragma once

#include <algorithm>
#include <cmath>

namespace mastrom::rom {

/// The polish's error on a sinusoid sampled at phase steps x = ωh, relative to its amplitude:
/// e(x) = 0.0234 x⁴, at most 2 (the samples may miss the peak entirely).
inline double polishError(double x) {
  const double x2 = x * x;
  return std::min(2.0, 0.0234 * x2 * x2);
}

/// The vertex of the parabola through (−1, v_minus), (0, v0), (1, v_plus) when it is a maximum
/// within [−1, 1]: its value and abscissa `offset`; false otherwise (the outputs then unset).
/// With v0 ≥ v_minus and v0 ≥ v_plus the abscissa is within ±½, so only the curvature decides.
inline bool parabolaMaximum(double v_minus, double v0, double v_plus, double& value,
                            double& offset) {
  const double bend = 2.0 * v0 - v_minus - v_plus;  // minus the second difference
  if (!(bend > 0.0)) return false;
  const double difference = v_plus - v_minus;
  const double at = 0.5 * difference / bend;
  if (std::abs(at) > 1.0) return false;
  offset = at;
  value = v0 + difference * difference / (8.0 * bend);
  return true;
}

/// The same through (−h_minus, v_minus), (0, v0), (h_plus, v_plus), h_minus, h_plus > 0: where a
/// refined node sequence changes its spacing (a step refined at another level than the one before
/// it), the three nodes are not equally spaced, and reading them as if they were moves the vertex
/// (measured: a peak 0.2 % low at a junction of 12.5 and 25 µs spacings). `offset` is in the
/// units of h. With h_minus = h_plus = 1 this is the function above.
inline bool parabolaMaximum(double v_minus, double v0, double v_plus, double h_minus,
                            double h_plus, double& value, double& offset) {
  const double slope_minus = (v0 - v_minus) / h_minus, slope_plus = (v_plus - v0) / h_plus;
  const double half_curvature = (slope_plus - slope_minus) / (h_minus + h_plus);
  if (!(half_curvature < 0.0)) return false;
  const double slope = slope_plus - half_curvature * h_plus;  // at the middle node
  const double at = -slope / (2.0 * half_curvature);
  if (at < -h_minus || at > h_plus) return false;
  offset = at;
  value = v0 - slope * slope / (4.0 * half_curvature);
  return true;
}

}  // namespace mastrom::rom
