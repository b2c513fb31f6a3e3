// Progress lines on stderr for long runs: at most one line every few seconds of wall time, each with
// the fraction done, the rate and an estimate of the time left. Quiet when stderr is not wanted.
#pragma once

#include <chrono>
#include <string>

namespace mastrom::cli {

class ProgressReporter {
public:
  /// @param label     prefix of every line, e.g. "simulate"
  /// @param interval_s minimum wall time between two lines
  explicit ProgressReporter(std::string label, double interval_s = 2.0, bool enabled = true);

  /// Report `done` of `total` (any unit, e.g. simulated seconds); `detail` is appended to the line.
  /// Prints when the interval has passed, or when done ≥ total (the final line).
  void update(double done, double total, const std::string& detail = "");

  double elapsedSeconds() const;

private:
  std::string label_;
  double interval_s_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_;
  bool finished_ = false;
};

}  // namespace mastrom::cli
