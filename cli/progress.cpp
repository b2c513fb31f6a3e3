#include "cli/progress.hpp"

#include <cstdio>

#include "cli/interrupt.hpp"

namespace mastrom::cli {

ProgressReporter::ProgressReporter(std::string label, double interval_s, bool enabled,
                                   ProgressUnit unit)
    : label_(std::move(label)),
      interval_s_(interval_s),
      enabled_(enabled),
      unit_(unit),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

double ProgressReporter::elapsedSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressReporter::update(double done, double total, const std::string& detail) {
  if (interruptRequested()) {
    char where[96];
    if (unit_ == ProgressUnit::kSimulatedSeconds)
      std::snprintf(where, sizeof where, "interrupted at t = %.6g s", done);
    else
      std::snprintf(where, sizeof where, "interrupted after %.0f of %.0f", done, total);
    throw Interrupted(label_ + ": " + where + "; no result written");
  }
  if (!enabled_ || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  const bool final_line = done >= total;
  if (!final_line && std::chrono::duration<double>(now - last_).count() < interval_s_) return;
  last_ = now;
  finished_ = final_line;
  const double elapsed = elapsedSeconds();
  const double fraction = total > 0 ? done / total : 1.0;
  const double left = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::fprintf(stderr, "%s: %5.1f%%  wall %.1f s  left ~%.0f s%s%s\n", label_.c_str(),
               100.0 * fraction, elapsed, left, detail.empty() ? "" : "  ", detail.c_str());
  std::fflush(stderr);
}

}  // namespace mastrom::cli
