// The full order's continuous response (docs/theory.md §5.4) while the steps are taken: step points
// go in one by one, and out come the outputs on the uniform grid t = k · output_step (and the last
// point itself) and the peaks of the continuous response, as soon as the interpolant that gives
// them is known. The memory is a window of the last four step points, whatever the horizon.
//
// Why four suffice: the output at τ ∈ [t_i, t_{i+1}) of a smooth piece uses the cubic through
// t_{i−1} … t_{i+2} (fewer at the piece's ends; fullorder/continuous_response.hpp cubicStencil).
// Once t_{i+2} has arrived — and the piece has at least four points, so the stencil's size no
// longer depends on where the piece ends — nothing later changes that cubic. At a breakpoint (a new
// piece) or the end, the rest of the piece is interpolated from its last four points. The window
// is handed to the same interpolation code as a whole series would be, with the same points in the
// same order, so the outputs and peaks equal resampleStepPoints() and continuousPeaks() bit for bit
// (those two are this stream fed with every point).
#pragma once

#include <cstddef>
#include <functional>

#include "fullorder/continuous_response.hpp"
#include "fullorder/deployment_result.hpp"

namespace mastrom::fullorder {

class StepPointStream {
public:
  /// Everything the stream's later outputs and peaks depend on (a checkpoint of a streamed adaptive
  /// run carries it, fullorder/checkpoint.hpp): restored into a stream of the same run, it goes on
  /// bit for bit as the uninterrupted one. A few step points, whatever the horizon.
  struct State {
    DeploymentSeries window;
    long piece_points = 0, next_interval = 0, next_output = 0;
    double first_time_s = 0.0;
    std::size_t points = 0;
    ContinuousPeaks peaks;
  };

  /// Receives each output instant, in time order.
  using Emit = std::function<void(const DeploymentSample&)>;

  /// output_step_s: spacing of the output grid (emit may be empty, then no outputs are made and
  /// output_step_s is ignored); drive_end_time_s: where the residual peak starts; subdivisions:
  /// instants per step at which the peaks look between points.
  StepPointStream(double output_step_s, double drive_end_time_s, DriveAt drive, Emit emit,
                  int subdivisions = 8);

  /// The next accepted step point (strictly later than the one before); piece_start: it opens a
  /// smooth piece of the drive (the first point always does, whatever is passed).
  void add(const DeploymentSample& point, bool piece_start);
  /// The record ends at the last point added: the rest of the outputs (the last point itself
  /// included) are emitted. Nothing may be added after.
  void finish();

  /// The state after the points added so far (UsageError after finish()).
  State state() const;
  /// Continue from `state` (of a stream with the same output step, drive and subdivisions).
  void restore(const State& state);

  const ContinuousPeaks& peaks() const { return peaks_; }
  std::size_t pointCount() const { return points_; }
  /// Bytes held: the window (a few step points), independent of the number of points.
  std::size_t windowSize() const { return window_.size(); }

private:
  /// Visit the peaks of intervals [t_i, t_{i+1}] for window indices i in [next_interval_, last).
  void visitIntervals(long last);
  /// Emit the output instants τ < limit from the window as the whole (closed: true) or the tail
  /// of the current piece.
  void emitBefore(double limit, bool closed);
  /// Close the current piece: its remaining intervals, the gap up to next_start (a breakpoint;
  /// none at the end), its remaining outputs.
  void closePiece(const double* next_start);

  double output_step_s_, drive_end_s_;
  DriveAt drive_;
  Emit emit_;
  int subdivisions_;
  DeploymentSeries window_;  ///< the current piece's last points (all of them while < 4)
  long piece_points_ = 0;    ///< points of the current piece so far
  long next_interval_ = 0;   ///< window index of the next interval whose peaks are not visited
  long next_output_ = 0;     ///< k of the next output instant t_first + k · output_step
  double first_time_s_ = 0.0;
  std::size_t points_ = 0;
  bool finished_ = false;
  ContinuousPeaks peaks_;
};

}  // namespace mastrom::fullorder
