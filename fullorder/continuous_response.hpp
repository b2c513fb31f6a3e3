// The full order's response between its step points (docs/theory.md §5.4): within each smooth piece
// of the drive (between breakpoints, where the integrator restarts) every output is interpolated by
// the cubic through the four nearest step points of that piece — fourth order, so the interpolation
// adds nothing visible to the integrator's second-order error — and the drive's own values are
// taken exactly from the law. Outputs on a uniform grid and the peaks of the continuous response
// (what the ROM's exact modal solution reports as its peaks) both come from this interpolant.
#pragma once

#include <functional>
#include <vector>

#include "fullorder/deployment_result.hpp"
#include "fullorder/drive_law.hpp"

namespace mastrom::fullorder {

/// The drive's θ, θ̇, θ̈ at a time (right limits at a breakpoint).
using DriveAt = std::function<DriveState(double)>;

/// Lagrange weights at τ of the (up to) four points of [begin, end) of `times` nearest to τ: the
/// interpolant of every output between step points (also used for the interface stresses,
/// fullorder/interface_stress.hpp). Value at τ = Σ_a weight[a] · column[first + a].
struct CubicStencil {
  long first = 0;
  int count = 0;
  double weight[4] = {0.0, 0.0, 0.0, 0.0};
};
CubicStencil cubicStencil(const std::vector<double>& times, long begin, long end, double tau);

/// Step points of a run: `steps` at every accepted step, `piece_starts` the index of the first point
/// of each smooth piece (ascending, the first is 0). A piece's interpolant is also used past its last
/// point up to the next piece's start (the left limit at a breakpoint, extrapolated).
struct StepPoints {
  const DeploymentSeries& steps;
  const std::vector<long>& piece_starts;
};

/// The outputs at τ from the interpolant of the piece [begin, end) of `points.steps` (the drive's
/// values exactly from the law; the solver diagnostics of the step that reached the next point).
DeploymentSample interpolateInPiece(const DeploymentSeries& steps, long begin, long end, double tau,
                                    const DriveAt& drive);

/// The outputs at t = k · output_step (k = 0, 1, …) up to the last step point, and at the last step
/// point itself. At a breakpoint that is also an output instant the right limit is reported.
/// (fullorder/step_point_stream.hpp does the same while the steps are taken.)
DeploymentSeries resampleStepPoints(const StepPoints& points, double output_step_s,
                                    const DriveAt& drive);

/// Peaks of the continuous response: the interpolant sampled at the step points and at
/// `subdivisions` evenly spaced instants inside every step (and between a piece's last point and
/// the next piece's first, on the earlier piece's interpolant).
struct ContinuousPeaks {
  double abs_end_angular_acceleration = 0.0;   ///< max |α_z| [rad/s²]
  double rel_end_angular_acceleration = 0.0;   ///< max |α_z − θ̈| [rad/s²]
  double residual_rel_end_angular_acceleration = 0.0;  ///< the same over t ≥ drive end [rad/s²]
  double joint_force = 0.0;                    ///< max ‖F‖ [N]
  double drive_torque = 0.0;                   ///< max |τ| [N·m]
  /// ∫ (α_z − θ̈)² dt over the record on the same interpolant [rad²/s³] (docs/theory.md §5.4:
  /// Gauss–Legendre on every step, exact for the cubic), and the span it covers [s].
  double square_rel_integral = 0.0;
  double square_span_s = 0.0;
};
ContinuousPeaks continuousPeaks(const StepPoints& points, double drive_end_time_s,
                                const DriveAt& drive, int subdivisions = 8);
/// Take the interpolant of the piece [begin, end) of `steps` at τ into the peaks.
void visitContinuousPeaks(const DeploymentSeries& steps, long begin, long end, double tau,
                          double drive_end_time_s, const DriveAt& drive, ContinuousPeaks& peaks);

/// Add ∫ (α_z − θ̈)² dt over [t0, t1] of the interpolant of the piece [begin, end) to the peaks.
void integrateContinuousSquare(const DeploymentSeries& steps, long begin, long end, double t0,
                               double t1, const DriveAt& drive, ContinuousPeaks& peaks);

/// Replace the peak metrics of `metrics` (taken from output samples) by the continuous ones where
/// those are larger (they always are, up to rounding: the samples lie on the interpolant), and the
/// RMS of α_z − θ̈ by the continuous one (the samples' trapezoidal rule errs by O(output.step)
/// at every jump of θ̈).
void applyContinuousPeaks(const ContinuousPeaks& peaks, DeploymentMetrics& metrics);

}  // namespace mastrom::fullorder
