// The full order at the tails of an uncertainty study (docs/theory.md §7.5): for every limit, the
// nonlinear full order re-runs the samples nearest the metric's 1 % and 99 % quantiles and the
// sample farthest into the event, and the ROM's value stands beside the full order's and the full
// order's own error estimate (fullorder/deployment_accuracy.hpp), so a user sees whether the tail
// the ROM draws is real. A sample shared by several checks runs once.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "rom/studies/uncertainty_study.hpp"

namespace mastrom::rom {

struct TailCheck {
  std::size_t limit = 0;  ///< index into UqResult::limits
  std::string label;      ///< "q01", "q99" or "critical"
  long row = -1;
  std::string metric;
  double rom_value = 0.0;
  double rom_error_bound = 0.0;  ///< the bound of uncertainty_errors.hpp (0: none)
  double full_value = 0.0;
  /// The full order's estimated absolute error of this metric: its own estimate of the peak where
  /// it has one (peaks of r, joint force), else its NRMSE estimate × |value|; NaN for fixed steps.
  double full_error_estimate = 0.0;
  double full_wall_s = 0.0;
};

/// The checks a study asks for (rows chosen, full-order fields not yet filled).
std::vector<TailCheck> tailChecks(const UqResult& result);

/// Run the full order at every distinct row of `checks` (serially, this process) and fill them in.
/// `progress(done, total)` after each run.
void runTailChecks(const RomDatabase& db, const Config& config, const UqResult& result,
                   std::vector<TailCheck>& checks,
                   const std::function<void(long, long)>& progress = {});
/// The same shared over the ranks of `comm` (collective; MPI_COMM_NULL: this process alone): the
/// distinct rows run on ranks 0, 1, … in turn, each run on one rank, and rank 0's `checks` are
/// filled in. `result` and `checks` are read on rank 0 only (the study's result lives there;
/// others may pass null). `progress(done, total)` counts this rank's own runs. A run that fails on
/// any rank throws the same error on every rank.
void runTailChecks(const RomDatabase& db, const Config& config, const UqResult* result,
                   std::vector<TailCheck>* checks, const std::function<void(long, long)>& progress,
                   MPI_Comm comm);

}  // namespace mastrom::rom
