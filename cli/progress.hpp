// Progress lines on stderr for long runs: at most one line every few seconds of wall time, each
// with the fraction done, the rate and an estimate of the time left. Quiet when stderr is not
// wanted. Every update is also where a run notices Ctrl-C (cli/interrupt.hpp): it throws
// Interrupted, whose message says how far the run got.
#pragma once

#include <chrono>
#include <string>

namespace mastrom::cli {

/// What `done` and `total` of ProgressReporter::update count (for the interruption message).
enum class ProgressUnit { kSimulatedSeconds, kItems };

class ProgressReporter {
public:
  /// @param label     prefix of every line, e.g. "simulate"
  /// @param interval_s minimum wall time between two lines
  /// @param unit      what update() counts: simulated seconds (a time integration) or items
  ///                  (samples, points, designs)
  explicit ProgressReporter(std::string label, double interval_s = 2.0, bool enabled = true,
                            ProgressUnit unit = ProgressUnit::kSimulatedSeconds);

  /// Report `done` of `total` (in the unit of the constructor); `detail` is appended to the line.
  /// Prints when the interval has passed, or when done ≥ total (the final line). Throws
  /// Interrupted, enabled or not, once SIGINT or SIGTERM has arrived.
  void update(double done, double total, const std::string& detail = "");

  double elapsedSeconds() const;

private:
  std::string label_;
  double interval_s_;
  bool enabled_;
  ProgressUnit unit_;
  std::chrono::steady_clock::time_point start_, last_;
  bool finished_ = false;
};

}  // namespace mastrom::cli
