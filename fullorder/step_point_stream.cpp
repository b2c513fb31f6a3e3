#include "fullorder/step_point_stream.hpp"

#include <utility>

#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {
/// Points a cubic needs; the window keeps this many of the current piece.
constexpr long kStencil = 4;
}  // namespace

StepPointStream::StepPointStream(double output_step_s, double drive_end_time_s, DriveAt drive,
                                 Emit emit, int subdivisions)
    : output_step_s_(output_step_s),
      drive_end_s_(drive_end_time_s),
      drive_(std::move(drive)),
      emit_(std::move(emit)),
      subdivisions_(subdivisions) {}

void StepPointStream::visitIntervals(long last) {
  const long end = static_cast<long>(window_.size());
  for (long i = next_interval_; i < last; ++i) {
    const double t0 = window_.time_s[static_cast<std::size_t>(i)];
    visitContinuousPeaks(window_, 0, end, t0, drive_end_s_, drive_, peaks_);
    if (i + 1 < end) {
      const double t1 = window_.time_s[static_cast<std::size_t>(i + 1)];
      integrateContinuousSquare(window_, 0, end, t0, t1, drive_, peaks_);
      for (int j = 1; j < subdivisions_; ++j)
        visitContinuousPeaks(window_, 0, end,
                             t0 + (t1 - t0) * static_cast<double>(j) / subdivisions_, drive_end_s_,
                             drive_, peaks_);
    }
  }
  if (last > next_interval_) next_interval_ = last;
}

void StepPointStream::emitBefore(double limit, bool) {
  if (!emit_) return;
  const long end = static_cast<long>(window_.size());
  for (;;) {
    // t = t_first + k·Δ, not a running sum, so the instants are the same in every run.
    const double tau = first_time_s_ + static_cast<double>(next_output_) * output_step_s_;
    if (!(tau < limit)) break;
    emit_(interpolateInPiece(window_, 0, end, tau, drive_));
    ++next_output_;
  }
}

void StepPointStream::add(const DeploymentSample& point, bool piece_start) {
  MASTROM_REQUIRE(!finished_, UsageError, "StepPointStream::add after finish()");
  if (points_ == 0) {
    first_time_s_ = point.time_s;
    piece_start = true;
  } else if (piece_start) {
    closePiece(&point.time_s);
  }
  if (piece_start) {
    window_ = DeploymentSeries{};
    piece_points_ = 0;
    next_interval_ = 0;
  }
  window_.append(point);
  ++piece_points_;
  ++points_;
  if (piece_points_ < kStencil) return;
  // The newest point n = end − 1 fixes the cubics of every τ < t_{n−1} (intervals up to n − 2).
  const long end = static_cast<long>(window_.size());
  visitIntervals(end - 2);
  emitBefore(window_.time_s[static_cast<std::size_t>(end - 2)], false);
  if (end > kStencil) {
    window_.dropFront(static_cast<std::size_t>(end - kStencil));
    next_interval_ -= end - kStencil;
  }
}

void StepPointStream::closePiece(const double* next_start) {
  const long end = static_cast<long>(window_.size());
  visitIntervals(end);
  if (next_start != nullptr) {
    // Up to the next piece's first point (a breakpoint): the left limit's side of the jump.
    const double t0 = window_.time_s.back();
    integrateContinuousSquare(window_, 0, end, t0, *next_start, drive_, peaks_);
    for (int j = 1; j < subdivisions_; ++j)
      visitContinuousPeaks(window_, 0, end,
                           t0 + (*next_start - t0) * static_cast<double>(j) / subdivisions_,
                           drive_end_s_, drive_, peaks_);
    emitBefore(*next_start, true);
  }
}

StepPointStream::State StepPointStream::state() const {
  MASTROM_REQUIRE(!finished_, UsageError, "StepPointStream::state after finish()");
  return State{window_,       piece_points_, next_interval_, next_output_,
               first_time_s_, points_,       peaks_};
}

void StepPointStream::restore(const State& state) {
  MASTROM_REQUIRE(!finished_ && state.window.size() <= static_cast<std::size_t>(kStencil) &&
                      (state.points == 0) == state.window.empty(),
                  UsageError, "StepPointStream::restore: a window of ", state.window.size(),
                  " points after ", state.points, " is not a stream's state");
  window_ = state.window;
  piece_points_ = state.piece_points;
  next_interval_ = state.next_interval;
  next_output_ = state.next_output;
  first_time_s_ = state.first_time_s;
  points_ = state.points;
  peaks_ = state.peaks;
}

void StepPointStream::finish() {
  MASTROM_REQUIRE(!finished_ && points_ > 0, UsageError,
                  "StepPointStream::finish: no step points, or finished already");
  closePiece(nullptr);
  const double t_last = window_.time_s.back();
  emitBefore(t_last, true);
  // The last step point itself (the end of the record), exactly.
  if (emit_)
    emit_(interpolateInPiece(window_, 0, static_cast<long>(window_.size()), t_last, drive_));
  finished_ = true;
}

}  // namespace mastrom::fullorder
